#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>

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

  /**
   * The expressions made here check every value they give: the first NaN or
   * infinite one is recorded (from any thread) with the entry, the formula and
   * where and when it was evaluated. throw_recorded_input_error() (collective
   * over @p comm) turns it into an InputError on every process.
   */
  void record_input_error(const std::string &message);
  void throw_recorded_input_error(MPI_Comm comm);

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
