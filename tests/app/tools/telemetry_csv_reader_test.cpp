// Telemetry CSV back into records: what format_telemetry_csv_row() wrote comes back, and a broken
// file is named with its line.
#include "app/tools/telemetry_csv_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace rovctl::app
