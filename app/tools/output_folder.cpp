// Creating and probing an output folder.
#include "app/tools/output_folder.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "app/runtime/errors.hpp"

namespace rovctl::app {

void prepare_output_folder(const std::string& command, const std::string& dir) {
  namespace fs = std::filesystem;
  const std::string what = "rovctl " + command + ": --out " + dir + ": ";
  if (dir.empty()) throw UsageError(what + "needs a folder");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec)) {
    throw UsageError(what + "cannot create the folder" +
                     (ec ? " (" + ec.message() + ")" : std::string(" (not a folder)")));
  }
  // Permissions alone do not say it (root, read-only mounts, /proc): write a file and remove it.
  const fs::path probe = fs::path(dir) / (".rovctl-write-probe-" + std::to_string(::getpid()));
  std::FILE* f = std::fopen(probe.c_str(), "w");
  const bool written = f != nullptr && std::fputs("probe\n", f) >= 0;
  const bool closed = f != nullptr && std::fclose(f) == 0;
  fs::remove(probe, ec);
  if (!written || !closed) throw UsageError(what + "cannot write into the folder");
}

}  // namespace rovctl::app
