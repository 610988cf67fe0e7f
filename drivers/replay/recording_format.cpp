// frames.csv writing and strict parsing.
#include "drivers/replay/recording_format.hpp"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rovctl::drivers {

namespace {

template <class T>
bool parse_integer(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  const auto [p, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && p == end;
}

bool safe_relative(const std::string& file) {
  if (file.empty()) return false;
  const std::filesystem::path p(file);
  if (p.is_absolute()) return false;
  for (const auto& part : p) {
    if (part == "..") return false;
  }
  return true;
}

}  // namespace

std::string frames_csv_row(const RecordedFrame& f) {
  return std::to_string(f.sequence) + "," + std::to_string(f.left_stamp.count()) + "," +
         std::to_string(f.right_stamp.count()) + "," + f.left_file + "," + f.right_file + "," +
         std::to_string(f.exposure.count()) + "\n";
}

bool read_frames_csv(const std::string& folder, std::vector<RecordedFrame>& frames,
                     std::string& error) {
  const std::string file = (std::filesystem::path(folder) / kFramesCsv).string();
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    error = file + ": cannot read (not a recorded dive? see deploy/recording-format.md)";
    return false;
  }
  std::stringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  frames.clear();
  std::size_t pos = 0;
  int line_no = 0;
  std::size_t columns = 6;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) break;  // unterminated: the recorder died while writing it
    std::string line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = file + ":" + std::to_string(line_no) + ": ";
    if (line_no == 1) {
      if (line == kFramesCsvHeaderWithoutExposure) {
        columns = 5;
      } else if (line != kFramesCsvHeader) {
        error = where + "expected the header '" + std::string(kFramesCsvHeader) + "' (or '" +
                kFramesCsvHeaderWithoutExposure + "')";
        return false;
      }
      continue;
    }
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream ls(line);
    for (std::string field; std::getline(ls, field, ',');) fields.push_back(field);
    // getline drops an empty last field: "...,png," is five fields, and so an error.
    if (fields.size() != columns) {
      error = where + "expected " + std::to_string(columns) + " fields, got " +
              std::to_string(fields.size());
      return false;
    }
    RecordedFrame f;
    long long left_ns = 0;
    long long right_ns = 0;
    if (!parse_integer(fields[0], f.sequence)) {
      error = where + "sequence: not a non-negative integer: '" + fields[0] + "'";
      return false;
    }
    if (!parse_integer(fields[1], left_ns) || !parse_integer(fields[2], right_ns)) {
      error = where + "left_stamp_ns/right_stamp_ns: not integers";
      return false;
    }
    f.left_stamp = std::chrono::nanoseconds(left_ns);
    f.right_stamp = std::chrono::nanoseconds(right_ns);
    f.left_file = fields[3];
    f.right_file = fields[4];
    long long exposure_ns = 0;
    if (columns == 6 && (!parse_integer(fields[5], exposure_ns) || exposure_ns < 0)) {
      error = where + "exposure_ns: not a non-negative integer: '" + fields[5] + "'";
      return false;
    }
    f.exposure = std::chrono::nanoseconds(exposure_ns);
    if (!safe_relative(f.left_file) || !safe_relative(f.right_file)) {
      error = where + "image file names must be relative paths inside the recording";
      return false;
    }
    frames.push_back(std::move(f));
  }
  if (line_no == 0) {
    error = file + ": empty (no header)";
    return false;
  }
  return true;
}

}  // namespace rovctl::drivers
