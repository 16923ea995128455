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
} // namespace anvil
