// `rovctl estimate`: placeholder until its issue lands (see commands.hpp).
#include <iostream>

#include "app/commands.hpp"
#include "app/errors.hpp"

namespace rovctl::app {

int command_estimate(const Words&) {
  std::cerr << "rovctl estimate: not implemented yet\n";
  return kExitRuntimeFailure;
}

}  // namespace rovctl::app
