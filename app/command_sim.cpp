// `rovctl sim`: placeholder until its issue lands (see commands.hpp).
#include <iostream>

#include "app/commands.hpp"
#include "app/errors.hpp"

namespace rovctl::app {

int command_sim(const Words&) {
  std::cerr << "rovctl sim: not implemented yet\n";
  return kExitRuntimeFailure;
}

}  // namespace rovctl::app
