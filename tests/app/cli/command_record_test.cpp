// `rovctl record` end to end on the replay backend: a recorded dive re-recorded pair for pair,
// and the start-up errors (exit 2) for a bad camera, a bad --out and a short recording of the mock
// camera.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"
#include "drivers/replay/dive_recorder.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

class CommandRecord : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rovctl_record_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    drivers::DiveRecorder recorder;
    std::string error;
    ASSERT_TRUE(recorder.open((dir_ / "source").string(), "", error)) << error;
    for (int i = 0; i < 4; ++i) {
      hal::StereoFrame f;
      f.left_bgr = cv::Mat(12, 16, CV_8UC3, cv::Scalar(10 * i, 20, 30));
      f.right_bgr = cv::Mat(12, 16, CV_8UC3, cv::Scalar(40, 50 + i, 60));
      f.left_stamp = std::chrono::milliseconds(1000 + 33 * i);
      f.right_stamp = f.left_stamp + std::chrono::milliseconds(1);
      f.sequence = static_cast<std::uint64_t>(i + 1);
      ASSERT_TRUE(recorder.write(f, error)) << error;
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string config(const std::string& camera_section) {
    const fs::path file = dir_ / "config.yaml";
    std::ofstream(file) << "calibration: " << ROVCTL_SOURCE_DIR
                        << "/deploy/config/stereo_calibration.yaml\n"
                        << camera_section;
    return file.string();
  }

  std::string replay_config() {
    return config("camera:\n  backend: replay\n  replay:\n    path: source\n    mode: tick\n");
  }

  static int rows(const fs::path& csv) {
    std::ifstream in(csv);
    int n = -1;  // the header
    for (std::string line; std::getline(in, line);) ++n;
    return n;
  }

  fs::path dir_;
};

TEST_F(CommandRecord, RecordsTheRequestedNumberOfPairs) {
  const std::string out = (dir_ / "out").string();
  EXPECT_EQ(command_record({"--config", replay_config(), "--out", out, "--frames", "3"}), kExitOk);
  EXPECT_EQ(rows(fs::path(out) / "frames.csv"), 3);
  EXPECT_TRUE(fs::is_regular_file(fs::path(out) / "stereo_calibration.yaml"));
  const cv::Mat left = cv::imread(out + "/left/000002.png");
  ASSERT_FALSE(left.empty());
  EXPECT_EQ(left.at<cv::Vec3b>(5, 5), cv::Vec3b(20, 20, 30));
}

TEST_F(CommandRecord, StopsAtTheEndOfAReplay) {
  const std::string out = (dir_ / "all").string();
  EXPECT_EQ(command_record({"--config", replay_config(), "--out", out}), kExitOk);
  EXPECT_EQ(rows(fs::path(out) / "frames.csv"), 4);
}

TEST_F(CommandRecord, StartUpErrorsNameTheProblem) {
  const std::string cfg = replay_config();
  try {
    command_record({"--config", cfg, "--out", (dir_ / "source").string()});
    ADD_FAILURE() << "recorded over an existing recording";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("not empty"), std::string::npos) << e.what();
  }
  const std::string missing =
      config("camera:\n  backend: replay\n  replay:\n    path: no_such_dive\n");
  try {
    command_record({"--config", missing, "--out", (dir_ / "x").string()});
    ADD_FAILURE() << "opened a missing recording";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_dive"), std::string::npos) << e.what();
  }
  const std::string v4l2 = config(
      "camera:\n  backend: v4l2\n  v4l2:\n    left_device: /dev/video-rovctl-none-l\n"
      "    right_device: /dev/video-rovctl-none-r\n");
  try {
    command_record({"--config", v4l2, "--out", (dir_ / "y").string()});
    ADD_FAILURE() << "opened a missing camera";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/video-rovctl-none-l"), std::string::npos)
        << e.what();
  }
  // The mock camera records the simulated world.
  EXPECT_EQ(
      command_record({"--config", config(""), "--out", (dir_ / "z").string(), "--frames", "2"}),
      kExitOk);
  EXPECT_TRUE(std::filesystem::exists(dir_ / "z" / "frames.csv"));
  EXPECT_THROW(command_record({"--config", cfg}), UsageError);
  EXPECT_THROW(command_record({"--config", cfg, "--out", "o", "--frames", "0"}), UsageError);
}

}  // namespace
}  // namespace rovctl::app
