// An output folder (`--out DIR`) proven writable before any work is done: a sweep of trials or a
// study must not find at its end that it cannot write what it computed.
#pragma once

#include <string>

namespace rovctl::app {

// Creates `dir` with its parents and writes and removes a probe file in it. Throws UsageError
// "<command>: --out DIR: <why>" (exit 2) when it cannot.
void prepare_output_folder(const std::string& command, const std::string& dir);

}  // namespace rovctl::app
