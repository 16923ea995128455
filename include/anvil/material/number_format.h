#pragma once

#include <string>

namespace anvil
{
  /// A value as a material message quotes it: 6 significant digits
  /// (temperatures, table bounds, parameters), shared by every law's errors.
  std::string short_number(double v);
} // namespace anvil
