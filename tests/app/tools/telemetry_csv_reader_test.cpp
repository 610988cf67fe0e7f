// Telemetry CSV back into records: what format_telemetry_csv_row() wrote comes back, and a broken
// file is named with its line.
#include "app/tools/telemetry_csv_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "estimator/pose_estimator.hpp"

namespace rovctl::app {
namespace {

std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("rovctl_csv_" + name)).string();
}

TEST(TelemetryCsvReader, ReadsBackWhatTheWriterWrote) {
  TelemetryRecord a;
  a.tick = 12;
  a.time_s = 0.396;
  a.mission_state = 3;
  a.fitness = 0.875;
  a.spheres_seen_left = 3;
  a.spheres_seen_right = 2;
  a.est_t_m = {0.01, -0.02, 0.45};
  a.est_q_wxyz = {1.0, 0.0, 0.0, 0.0};
  a.dock_lateral_error_m = 0.004;
  a.thruster_count = 8;
  a.thruster_cmd[7] = -0.125;
  a.bus_status = 1;
  a.error_bound_m = 0.0125;
  a.error_bound_deg = 3.25;
  a.not_ok_reason = static_cast<std::int32_t>(estimator::NotOkReason::partial_view);
  a.flags = telemetry_flag::estimate_valid | telemetry_flag::operator_hold;
  TelemetryRecord b;  // NaN fields stay NaN
  b.tick = 13;
  const std::string path = temp_file("roundtrip.csv");
  {
    std::ofstream out(path);
    char row[4096];
    out << telemetry_csv_header() << "\n";
    out.write(row, static_cast<std::streamsize>(format_telemetry_csv_row(a, row, sizeof(row))));
    out << "\n";
    out.write(row, static_cast<std::streamsize>(format_telemetry_csv_row(b, row, sizeof(row))));
    out << "\n";
  }
  const std::vector<TelemetryRecord> got = read_telemetry_csv(path);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].tick, 12u);
  EXPECT_DOUBLE_EQ(got[0].time_s, 0.396);
  EXPECT_EQ(got[0].mission_state, 3);
  EXPECT_DOUBLE_EQ(got[0].fitness, 0.875);
  EXPECT_EQ(got[0].spheres_seen_right, 2);
  EXPECT_DOUBLE_EQ(got[0].est_t_m[2], 0.45);
  EXPECT_DOUBLE_EQ(got[0].dock_lateral_error_m, 0.004);
  EXPECT_EQ(got[0].thruster_count, 8);
  EXPECT_DOUBLE_EQ(got[0].thruster_cmd[7], -0.125);
  EXPECT_EQ(got[0].flags, a.flags);
  EXPECT_EQ(got[0].not_ok_reason, a.not_ok_reason);
  EXPECT_EQ(got[1].not_ok_reason, 0);  // none
  EXPECT_DOUBLE_EQ(got[0].error_bound_m, 0.0125);
  EXPECT_DOUBLE_EQ(got[0].error_bound_deg, 3.25);
  EXPECT_TRUE(std::isnan(got[1].error_bound_deg));
  EXPECT_TRUE(std::isnan(got[1].fitness));
  EXPECT_TRUE(std::isnan(got[1].est_t_m[0]));
  std::filesystem::remove(path);
}

TEST(TelemetryCsvReader, NamesTheFileAndLineOfABrokenRow) {
  const std::string path = temp_file("broken.csv");
  {
    std::ofstream out(path);
    TelemetryRecord r;
    char row[4096];
    out << telemetry_csv_header() << "\n";
    out.write(row, static_cast<std::streamsize>(format_telemetry_csv_row(r, row, sizeof(row))));
    out << "\n1,2,3\n";
  }
  try {
    read_telemetry_csv(path);
    FAIL() << "a short row must be an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3:"), std::string::npos) << e.what();
  }
  {
    std::ofstream out(path);
    out << "time,x\n1,2\n";
  }
  try {
    read_telemetry_csv(path);
    FAIL() << "a CSV without rovctl's columns must be an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":1: no column 'tick'"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

// A recording made before the column existed still replays; a word the column cannot hold is an
// error naming the file, line and column.
TEST(TelemetryCsvReader, TheNotOkReasonIsOptionalButNeverGuessed) {
  const std::string path = temp_file("reason.csv");
  TelemetryRecord r;
  r.tick = 4;
  r.not_ok_reason = static_cast<std::int32_t>(estimator::NotOkReason::bound_over_limit);
  char row[4096];
  const std::string header = telemetry_csv_header();
  const std::string line(row, format_telemetry_csv_row(r, row, sizeof(row)));
  // The column's index in the header, to cut it out of both lines or replace its cell.
  std::size_t column = 0;
  for (std::size_t i = 0; i < header.find("not_ok_reason"); ++i) column += header[i] == ',';
  const auto without = [&](const std::string& csv) {
    std::size_t start = 0;
    for (std::size_t c = 0; c < column; ++c) start = csv.find(',', start) + 1;
    return csv.substr(0, start) + csv.substr(csv.find(',', start) + 1);
  };
  {
    std::ofstream out(path);
    out << without(header) << "\n" << without(line) << "\n";
  }
  const std::vector<TelemetryRecord> old = read_telemetry_csv(path);
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].tick, 4u);
  EXPECT_EQ(old[0].not_ok_reason, 0);
  {
    std::ofstream out(path);
    out << header << "\n" << line << "\n";
  }
  EXPECT_EQ(read_telemetry_csv(path)[0].not_ok_reason, r.not_ok_reason);
  {
    std::ofstream out(path);
    std::string bad = line;
    bad.replace(bad.find("bound_over_limit"), 16, "partial");
    out << header << "\n" << bad << "\n";
  }
  try {
    read_telemetry_csv(path);
    FAIL() << "an unknown reason must be an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2: column 'not_ok_reason'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("'partial'"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rovctl::app
