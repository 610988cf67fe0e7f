// A number as the messages and tables write it; not for the tick (it allocates).
#include "hal/primitives/number_format.hpp"

#include <sstream>

namespace rovctl::hal {

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace rovctl::hal
