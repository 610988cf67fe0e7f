// rename(2) within one directory is atomic, so readers see the old file or the whole new one.
#include "app/tools/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rovctl::app {

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f) throw std::runtime_error(path + ": cannot write");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace rovctl::app
