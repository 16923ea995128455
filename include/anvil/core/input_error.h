#pragma once

#include <stdexcept>
#include <string>

namespace anvil
{
  /**
   * A problem with the user's input: a scene file entry, a command-line
   * override, a mesh file. The message is one line and names the file,
   * line (where known), parameter and what was expected. main() prints it
   * as "anvil: error: <message>" and exits with status 2, before any work.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * A failure during the simulation that the time stepper could not recover
   * from (minimum step reached, inverted elements, ...). What was computed is
   * written before this propagates; main() exits with status 3.
   */
  class SimulationError : public std::runtime_error
  {
  public:
    explicit SimulationError(const std::string &message)
      : std::runtime_error(message)
    {}
  };
} // namespace anvil
