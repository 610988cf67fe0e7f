// The inverse of format_telemetry_csv_row(): columns found by header name ("nan" stays NaN).
#include "app/tools/telemetry_csv_reader.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "estimator/pose_estimator.hpp"

namespace rovctl::app {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

std::vector<TelemetryRecord> read_telemetry_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ":1: empty file, no header");
  std::map<std::string, std::size_t> column;
  const std::vector<std::string> header = split(line);
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  const auto index = [&](const std::string& name) {
    const auto it = column.find(name);
    if (it == column.end()) {
      throw std::runtime_error(path + ":1: no column '" + name + "' (not a rovctl telemetry CSV)");
    }
    return it->second;
  };
  // Every field the replay shows; looked up once.
  const std::size_t c_tick = index("tick"), c_time = index("time_s"),
                    c_state = index("mission_state"), c_fit = index("fitness"),
                    c_sl = index("spheres_left"), c_sr = index("spheres_right"),
                    c_bound = index("error_bound_m"), c_x = index("est_x_m"),
                    c_qw = index("est_qw"), c_lat = index("dock_lateral_m"),
                    c_ax = index("dock_axial_m"), c_yaw = index("dock_yaw_rad"),
                    c_count = index("thruster_count"), c_cmd0 = index("cmd0"),
                    c_bus = index("bus_status"), c_flags = index("flags");
  // Recordings made before these columns existed read as "none" and no rotation bound.
  const auto reason_column = column.find("not_ok_reason");
  const auto bound_deg_column = column.find("error_bound_deg");
  std::vector<TelemetryRecord> records;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != header.size()) {
      throw std::runtime_error(path + ":" + std::to_string(line_no) + ": " +
                               std::to_string(cells.size()) + " fields, the header has " +
                               std::to_string(header.size()));
    }
    const auto number = [&](std::size_t c) {
      const std::string& s = cells[c];
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(s.c_str(), &end);
      if (s.empty() || end == s.c_str() || *end != '\0') {
        throw std::runtime_error(path + ":" + std::to_string(line_no) + ": column '" + header[c] +
                                 "' is not a number: '" + s + "'");
      }
      return v;
    };
    TelemetryRecord r;
    r.tick = static_cast<std::uint64_t>(number(c_tick));
    r.time_s = number(c_time);
    r.mission_state = static_cast<std::int32_t>(number(c_state));
    r.fitness = number(c_fit);
    r.spheres_seen_left = static_cast<std::int32_t>(number(c_sl));
    r.spheres_seen_right = static_cast<std::int32_t>(number(c_sr));
    r.error_bound_m = number(c_bound);
    if (bound_deg_column != column.end()) r.error_bound_deg = number(bound_deg_column->second);
    if (reason_column != column.end()) {
      const std::string& token = cells[reason_column->second];
      estimator::NotOkReason reason = estimator::NotOkReason::none;
      if (!estimator::from_string(token, reason)) {
        throw std::runtime_error(path + ":" + std::to_string(line_no) +
                                 ": column 'not_ok_reason' is not none, partial_view, not_refined, "
                                 "bound_over_limit or unconfirmed: '" +
                                 token + "'");
      }
      r.not_ok_reason = static_cast<std::int32_t>(reason);
    }
    for (std::size_t i = 0; i < 3; ++i) r.est_t_m[i] = number(c_x + i);
    for (std::size_t i = 0; i < 4; ++i) r.est_q_wxyz[i] = number(c_qw + i);
    r.dock_lateral_error_m = number(c_lat);
    r.dock_axial_error_m = number(c_ax);
    r.dock_yaw_error_rad = number(c_yaw);
    r.thruster_count = static_cast<std::int32_t>(number(c_count));
    for (std::size_t i = 0; i < r.thruster_cmd.size(); ++i) r.thruster_cmd[i] = number(c_cmd0 + i);
    r.bus_status = static_cast<std::int32_t>(number(c_bus));
    r.flags = static_cast<std::uint32_t>(number(c_flags));
    records.push_back(r);
  }
  return records;
}

}  // namespace rovctl::app
