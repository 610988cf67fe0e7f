// Output files that are never seen half-written: write a temporary beside the target, then rename.
#pragma once

#include <string>

namespace rovctl::app {

// Throws std::runtime_error naming `path` if it cannot be written.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace rovctl::app
