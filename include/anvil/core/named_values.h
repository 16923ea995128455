#pragma once

#include <anvil/core/input_error.h>

#include <map>
#include <string>

namespace anvil
{
  /**
   * Scalars of a committed state by name (checkpoints): a restart reads them
   * by name, so adding one never shifts the others, and a missing one is
   * named in the error instead of being read as a neighbour's value.
   */
  using NamedValues = std::map<std::string, double>;

  inline double named_value(const NamedValues &values, const std::string &key)
  {
    const auto it = values.find(key);
    if (it == values.end())
      throw InputError("the checkpoint has no entry '" + key +
                       "' (written by another version of anvil, or damaged)");
    return it->second;
  }
} // namespace anvil
