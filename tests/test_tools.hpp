// The helper programs some tests drive (pymodbus as an independent Modbus controller, socat for
// pseudo-terminals). deploy/setup.sh installs them, so under CI a missing one fails the test
// instead of skipping it: a skip there would hide a broken setup script.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace rovctl::test {

inline bool have_pymodbus() {
  return std::system("/usr/bin/python3 -c 'import pymodbus.server.async_io' >/dev/null 2>&1") == 0;
}

inline bool have_socat() { return std::system("command -v socat >/dev/null 2>&1") == 0; }

inline bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

}  // namespace rovctl::test

// Skips (or, under CI=true, fails) the current test when `available` is false.
#define ROVCTL_REQUIRE_TOOL(available, what)                                                 \
  do {                                                                                       \
    if (!(available)) {                                                                      \
      if (::rovctl::test::in_ci()) FAIL() << what << " (deploy/setup.sh should install it)"; \
      GTEST_SKIP() << what;                                                                  \
    }                                                                                        \
  } while (0)
