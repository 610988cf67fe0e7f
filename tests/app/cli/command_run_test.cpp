// `rovctl run` on the bench set-up: a replayed dive for the cameras and a Modbus TCP thruster
// controller (pymodbus, an independent implementation) for the thrusters. The controller must
// see commands and heartbeats at the 30 Hz tick rate, and neutral + disarmed at the end.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "drivers/replay/dive_recorder.hpp"
#include "estimator/stereo_calibration.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "modbus_peer.hpp"
#include "test_tools.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

std::string write_recording(const std::string& dir, const std::string& calibration) {
  const hal::StereoRig rig = estimator::load_stereo_calibration(calibration);
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  const hal::mock::RenderOptions options;
  const hal::mock::SceneRenderer left(rig.left, marker, options);
  const hal::mock::SceneRenderer right(rig.right, marker, options);
  drivers::DiveRecorder recorder;
  std::string error;
  const std::string folder = dir + "/dive";
  EXPECT_TRUE(recorder.open(folder, calibration, error)) << error;
  hal::StereoFrame frame;
  for (int i = 0; i < 6; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.05 + 0.002 * i, 0.01, 0.9);
    hal::mock::render_stereo(left, right, rig, T, static_cast<std::uint64_t>(i), frame.left_bgr,
                             frame.right_bgr);
    frame.sequence = static_cast<std::uint64_t>(i);
    frame.left_stamp = frame.right_stamp = std::chrono::milliseconds(33 * i);
    EXPECT_TRUE(recorder.write(frame, error)) << error;
  }
  recorder.close();
  return folder;
}

TEST(CommandRun, ReplayAndModbusControllerHold30Hz) {
  ROVCTL_REQUIRE_TOOL(test::have_pymodbus(), "/usr/bin/python3 has no usable pymodbus");
  const std::string dir = fs::temp_directory_path() / ("rovctl-run-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string calibration =
      std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/stereo_calibration.yaml";
  const std::string dive = write_recording(dir, calibration);

  test::ModbusPeer controller;
  ASSERT_TRUE(controller.start()) << "the pymodbus controller did not start";
  const std::string log = controller.log();

  const std::string config = dir + "/bench.yaml";
  {
    std::ofstream out(config);
    out << "calibration: " << calibration << "\n"
        << "camera:\n  backend: replay\n  replay:\n    path: " << dive
        << "\n    mode: tick\n    loop: true\n"
        << "thruster_bus:\n  backend: modbus\n  modbus:\n    transport: tcp\n    host: 127.0.0.1\n"
        << "    port: " << controller.port() << "\n    slave_id: 7"
        << "\n    response_timeout_ms: 200\n"
        // The peer's fault flags (0x100 + channel) and rpm (3 x permille) are a register-mapping
        // pattern, not an ESC's: judged as health they fail every thruster at tick 2.
        << "control:\n  thruster_health:\n    enabled: false\n";
  }
  const int ticks = 150;  // 5 s at 30 Hz
  const auto t0 = std::chrono::steady_clock::now();
  const int code = command_run({"--config", config, "--max-ticks", std::to_string(ticks), "--quiet",
                                "--telemetry", dir + "/telemetry.csv"});
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The scheduler's own count of skipped releases (telemetry column skipped_total): when another
  // process starves this 2-core machine the loop cannot hold its deadlines, and the rate at the
  // controller says nothing about rovctl. Then the test reports itself skipped with the load
  // measured, never passed.
  long skipped = -1;
  {
    std::ifstream csv(dir + "/telemetry.csv");
    std::string header, row, last;
    std::getline(csv, header);
    while (std::getline(csv, row)) last = row;
    std::size_t column = 0;
    std::istringstream hs(header);
    std::string name;
    while (std::getline(hs, name, ',') && name != "skipped_total") ++column;
    std::istringstream rs(last);
    std::string cell;
    for (std::size_t i = 0; i <= column && std::getline(rs, cell, ','); ++i) {
    }
    skipped = std::atol(cell.c_str());
  }
  ASSERT_GE(skipped, 0) << "telemetry.csv has no skipped_total";
  if (skipped > ticks / 20) {
    fs::remove_all(dir);
    double load[3] = {-1.0, -1.0, -1.0};
    getloadavg(load, 3);
    GTEST_SKIP() << "the machine is too loaded to hold 33 ms here: " << skipped
                 << " releases skipped in " << ticks << " ticks (" << wall_s << " s), load average "
                 << load[0] << " " << load[1] << " " << load[2] << " on "
                 << std::thread::hardware_concurrency() << " CPUs";
  }
  // Checked once the machine is known to hold the period: a starved loop trips the failsafe's
  // cpu overrun streak and `run` ends non-zero.
  EXPECT_EQ(code, kExitOk);
  EXPECT_NEAR(wall_s, ticks * 0.033, 1.0);

  // What arrived at the controller: heartbeats (register 16) and command blocks (registers 0-7).
  std::ifstream in(log);
  std::string line;
  std::vector<double> heartbeat_s, command_s;
  std::vector<std::string> last_writes;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    double t;
    std::string kind;
    int address;
    if (!(ls >> t >> kind >> address) || kind != "hr") continue;
    if (address == 16) heartbeat_s.push_back(t);
    if (address == 0) command_s.push_back(t);
    last_writes.push_back(line.substr(line.find("hr")));
  }
  ASSERT_GE(heartbeat_s.size(), static_cast<std::size_t>(ticks - 5));
  ASSERT_GE(command_s.size(), static_cast<std::size_t>(ticks - 5));
  const double hb_rate = (heartbeat_s.size() - 1) / (heartbeat_s.back() - heartbeat_s.front());
  const double cmd_rate = (command_s.size() - 1) / (command_s.back() - command_s.front());
  EXPECT_NEAR(hb_rate, 1000.0 / 33.0, 2.0) << "heartbeats per second at the controller";
  EXPECT_NEAR(cmd_rate, 1000.0 / 33.0, 2.0) << "command blocks per second at the controller";
  RecordProperty("heartbeat_hz", std::to_string(hb_rate));
  std::cout << "controller saw " << heartbeat_s.size() << " heartbeats at " << hb_rate << " Hz, "
            << command_s.size() << " command blocks at " << cmd_rate << " Hz\n";
  // The last thing the controller hears is neutral and disarmed.
  ASSERT_GE(last_writes.size(), 2u);
  bool neutral_then_disarmed = false;
  for (std::size_t i = 0; i + 1 < last_writes.size(); ++i) {
    if (last_writes[i] == "hr 0 0 0 0 0 0 0 0 0") {
      for (std::size_t j = i + 1; j < last_writes.size(); ++j) {
        neutral_then_disarmed = neutral_then_disarmed || last_writes[j] == "hr 17 0";
      }
    }
  }
  EXPECT_TRUE(neutral_then_disarmed) << "last write: " << last_writes.back();
  EXPECT_TRUE(fs::exists(dir + "/telemetry.csv"));
  fs::remove_all(dir);
}

TEST(CommandRun, MissingDeviceIsAStartUpErrorNamingIt) {
  const std::string dir =
      fs::temp_directory_path() / ("rovctl-run-bad-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string config = dir + "/bad.yaml";
  {
    std::ofstream out(config);
    out << "calibration: " << ROVCTL_SOURCE_DIR << "/deploy/config/stereo_calibration.yaml\n"
        << "camera:\n  backend: v4l2\n  v4l2:\n    left_device: /dev/video-missing-left\n"
        << "    right_device: /dev/video-missing-right\n";
  }
  try {
    command_run({"--config", config, "--max-ticks", "3", "--quiet"});
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/video-missing-left"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rovctl::app
