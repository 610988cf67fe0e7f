// A std::chrono duration as seconds in a double: the unit the parameters and the physics speak.
#pragma once

#include <chrono>

namespace rovctl::hal {

inline double seconds(std::chrono::nanoseconds d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace rovctl::hal
