#pragma once

// The "Direct solver limit" entries of the mechanics and of the heat: a
// number of DoFs, or "measured" for the crossover measured for the system.
#include <anvil/core/scene.h>

#include <stdexcept>
#include <string>

namespace anvil
{
  /// @p text as a number of DoFs >= 0, or @p measured for "measured"; anything
  /// else fails the scene at @p path.
  inline unsigned int parse_dof_limit(const std::string &text, const unsigned int measured, const Scene &scene,
                                      const std::string &path)
  {
    if (text == "measured")
      return measured;
    std::size_t used = 0;
    long        n    = -1;
    try
      {
        n = std::stol(text, &used);
      }
    catch (const std::exception &)
      {
      }
    if (n < 0 || used != text.size())
      scene.fail(path, "= '" + text + "': expected a number of DoFs >= 0 or 'measured'");
    return static_cast<unsigned int>(n);
  }
} // namespace anvil
