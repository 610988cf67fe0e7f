// Output files that are never seen half-written: write a temporary beside the target, then rename.
#pragma once

#include <functional>
#include <string>

namespace rovctl::app {

// Throws std::runtime_error naming `path` if it cannot be written.
void write_file_atomically(const std::string& path, const std::string& text);
// The same, with `check` run on the written temporary before it replaces `path`: what `check`
// throws leaves `path` as it was and the temporary removed.
void write_file_atomically(const std::string& path, const std::string& text,
                           const std::function<void(const std::string& written)>& check);

}  // namespace rovctl::app
