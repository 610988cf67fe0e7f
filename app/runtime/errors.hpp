// The two kinds of start-up error the CLI maps to exit code 2: bad command line, bad config/input.
#pragma once

#include <stdexcept>
#include <string>

namespace rovctl::app {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad configuration or input file; the message names the file, line and key where known.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Exit codes (README.md): success, run-time failure, usage or config error.
constexpr int kExitOk = 0;
constexpr int kExitRuntimeFailure = 1;
constexpr int kExitUsage = 2;

}  // namespace rovctl::app
