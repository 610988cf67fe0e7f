// `rovctl run`: placeholder until its issue lands (see commands.hpp).
#include <iostream>

#include "app/commands.hpp"
#include "app/errors.hpp"

namespace rovctl::app {

int command_run(const Words&) {
  std::cerr << "rovctl run: not implemented yet\n";
  return kExitRuntimeFailure;
}

}  // namespace rovctl::app
