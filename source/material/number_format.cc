#include <anvil/material/number_format.h>

#include <sstream>

namespace anvil
{
  std::string short_number(const double v)
  {
    std::ostringstream o;
    o << v;
    return o.str();
  }
} // namespace anvil
