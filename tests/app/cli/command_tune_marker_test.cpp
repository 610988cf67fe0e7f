// `rovctl tune-marker` end to end on the committed cast sample: the fragment and a figure per
// view written, and every refusal (not a recording, an existing --out, a marker that cannot be
// located) exit 2 with nothing written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

const std::string kSample = std::string(ROVCTL_TEST_DATA_DIR) + "/marker_colour_cast";
const std::string kConfig = std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/sim.yaml";

class CommandTuneMarker : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rovctl_tune_marker_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(CommandTuneMarker, WritesTheFragmentAndAFigurePerView) {
  const int code =
      command_tune_marker({"--config", kConfig, "--pairs", kSample, "--out", path("tuned.yaml")});
  EXPECT_EQ(code, kExitOk);
  std::ifstream in(path("tuned.yaml"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("marker:\n  spheres:\n    - name: red"), std::string::npos) << text;
  int figures = 0;
  for (const auto& e : fs::directory_iterator(path("tuned-segmentation"))) {
    const cv::Mat f = cv::imread(e.path().string());
    EXPECT_EQ(f.cols, 3 * 640) << e.path();
    ++figures;
  }
  EXPECT_EQ(figures, 2 * 3);
  // A second run does not overwrite what the first wrote, unless asked.
  EXPECT_THROW(
      command_tune_marker({"--config", kConfig, "--pairs", kSample, "--out", path("tuned.yaml")}),
      UsageError);
}

TEST_F(CommandTuneMarker, AFolderThatIsNotARecordingIsAConfigError) {
  fs::create_directories(path("empty"));
  EXPECT_THROW(
      command_tune_marker({"--config", kConfig, "--pairs", path("empty"), "--out", path("t.yaml")}),
      ConfigError);
  EXPECT_THROW(command_tune_marker(
                   {"--config", kConfig, "--pairs", path("absent"), "--out", path("t.yaml")}),
               ConfigError);
  EXPECT_FALSE(fs::exists(path("t.yaml")));
  EXPECT_FALSE(fs::exists(path("t-segmentation")));
}

TEST_F(CommandTuneMarker, AMarkerThatCannotBeLocatedIsRefusedWithNothingWritten) {
  // One pair of open water: nothing to tune on.
  fs::create_directories(path("rec/left"));
  fs::create_directories(path("rec/right"));
  const cv::Mat water(480, 640, CV_8UC3, cv::Scalar(60, 110, 70));
  cv::imwrite(path("rec/left/000000.png"), water);
  cv::imwrite(path("rec/right/000000.png"), water);
  std::ofstream(path("rec/frames.csv"))
      << "sequence,left_stamp_ns,right_stamp_ns,left_file,right_file\n"
      << "0,1000,1000,left/000000.png,right/000000.png\n";
  const int code = command_tune_marker(
      {"--config", kConfig, "--pairs", path("rec"), "--out", path("t.yaml"), "--frames", "2"});
  EXPECT_EQ(code, kExitUsage);
  EXPECT_FALSE(fs::exists(path("t.yaml")));
  EXPECT_FALSE(fs::exists(path("t-segmentation")));
}

TEST_F(CommandTuneMarker, RequiredOptionsAreNamed) {
  try {
    command_tune_marker({"--config", kConfig, "--pairs", kSample});
    FAIL() << "no --out accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--out"), std::string::npos) << e.what();
  }
}

TEST_F(CommandTuneMarker, AWorkingRangeThatDoesNotParseIsAUsageErrorNamingIt) {
  for (const char* bad : {"1.5", "1.5,0.3", "0.3,1.5x", "0,1", "0.3,40"}) {
    try {
      command_tune_marker(
          {"--config", kConfig, "--pairs", kSample, "--out", path("t.yaml"), "--range-m", bad});
      FAIL() << bad << " accepted";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--range-m ") + bad), std::string::npos)
          << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(path("t.yaml")));
}

}  // namespace
}  // namespace rovctl::app
