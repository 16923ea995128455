#pragma once

#include <deal.II/base/function_parser.h>

#include <memory>
#include <string>

namespace anvil
{
  class Scene;

  /**
   * One muparser expression in the coordinates x, y (, z) and time t, with the
   * constant pi, as a scalar FunctionParser. A syntax error or an unknown name
   * is an InputError via scene.fail(path, ...) that quotes muparser's reason.
   */
  template <int dim>
  std::shared_ptr<dealii::FunctionParser<dim>> parse_expression(const std::string &expression,
                                                                const Scene       &scene,
                                                                const std::string &path);

  /// The same with other variables (e.g. "t" for dim = 1, not time dependent);
  /// @p what (optional) says what the expression is for in the message.
  template <int dim>
  std::shared_ptr<dealii::FunctionParser<dim>> parse_expression(const std::string &expression,
                                                                const std::string &variables,
                                                                bool               time_dependent,
                                                                const Scene       &scene,
                                                                const std::string &path,
                                                                const std::string &what);
} // namespace anvil
