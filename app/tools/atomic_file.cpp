// rename(2) within one directory is atomic, so readers see the old file or the whole new one.
#include "app/tools/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rovctl::app {

void write_file_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, text, [](const std::string&) {});
}

void write_file_atomically(const std::string& path, const std::string& text,
                           const std::function<void(const std::string& written)>& check) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f) throw std::runtime_error(path + ": cannot write");
  }
  try {
    check(tmp);
  } catch (...) {
    std::filesystem::remove(tmp);
    throw;
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace rovctl::app
