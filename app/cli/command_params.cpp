// `rovctl params`: the declared parameters with units, ranges, defaults (or the config's values).
#include <iostream>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/config_loader.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {

int command_params(const Words& words) {
  const CliArgs args = CliArgs::parse("params", words, {"--config"}, {});
  AppConfig config;
  if (args.has("--config")) config = load_app_config(args.get("--config"));
  std::cout << describe_parameters_markdown(
      [&config](hal::ParamVisitor& v) { describe(v, config); });
  return kExitOk;
}

}  // namespace rovctl::app
