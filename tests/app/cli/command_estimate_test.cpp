// `rovctl estimate` on rendered PNGs of the shipped calibration, and every kind of bad input:
// one ConfigError/UsageError line (exit code 2 in main) naming the file or key, no pose printed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"
#include "estimator/stereo_calibration.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/model/pose.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

const std::string kCalibration =
    std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/stereo_calibration.yaml";

struct Files {
  // One folder per test: ctest runs this file's tests as parallel processes, and one test
  // rewriting left.png while another reads it failed a run.
  fs::path dir = fs::temp_directory_path() /
                 ("rovctl_command_estimate_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::string left, right, config;
  Eigen::Isometry3d truth = hal::make_pose(
      {0.04, -0.02, 0.55},
      Eigen::Quaterniond(Eigen::AngleAxisd(0.25, Eigen::Vector3d(0.3, 1.0, 0.2).normalized())));

  Files() {
    fs::create_directories(dir);
    const hal::StereoRig rig = estimator::load_stereo_calibration(kCalibration);
    const hal::MarkerModel marker = hal::MarkerModel::standard();
    const hal::mock::RenderOptions o;
    const hal::mock::SceneRenderer l(rig.left, marker, o), r(rig.right, marker, o);
    cv::Mat lb, rb;
    hal::mock::render_stereo(l, r, rig, truth, 7, lb, rb);
    left = (dir / "left.png").string();
    right = (dir / "right.png").string();
    cv::imwrite(left, lb);
    cv::imwrite(right, rb);
    config = write("config.yaml", "calibration: " + kCalibration + "\n");
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
};

std::vector<double> numbers_after(const std::string& json, const std::string& key) {
  std::vector<double> out;
  std::size_t i = json.find("\"" + key + "\": ");
  if (i == std::string::npos) return out;
  i += key.size() + 4;
  const bool array = json[i] == '[';
  if (array) ++i;
  while (true) {
    std::size_t used = 0;
    out.push_back(std::stod(json.substr(i), &used));
    i += used;
    if (!array || json[i] != ',') break;
    i += 2;
  }
  return out;
}

TEST(CommandEstimate, FindsThePoseInARenderedPair) {
  const Files f;
  ::testing::internal::CaptureStdout();
  const int rc = command_estimate(
      {"--config", f.config, "--left", f.left, "--right", f.right, "--seed", "3", "--json"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  ASSERT_EQ(rc, kExitOk) << out;
  EXPECT_EQ(out.find('\n'), out.size() - 1);  // exactly one line, one object
  EXPECT_NE(out.find("\"ok\": true"), std::string::npos);
  const std::vector<double> t = numbers_after(out, "t_cl_marker_m");
  const std::vector<double> q = numbers_after(out, "q_cl_marker_wxyz");
  ASSERT_EQ(t.size(), 3u);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_LT((Eigen::Vector3d(t[0], t[1], t[2]) - f.truth.translation()).norm(), 0.002);
  const Eigen::Quaterniond qe(q[0], q[1], q[2], q[3]);
  EXPECT_LT(hal::rotation_angle_rad(qe.toRotationMatrix(), f.truth.linear()), M_PI / 180.0);
  EXPECT_GE(numbers_after(out, "fitness").at(0), 0.9);
  EXPECT_GT(numbers_after(out, "generations").at(0), 0.0);
  EXPECT_GT(numbers_after(out, "time_ms").at(0), 0.0);
}

TEST(CommandEstimate, AnEstimateNotOkSaysWhichTestItFailedAndByWhichKey) {
  const Files f;
  // Every sphere seen and the pose right, but the rotation bound held to 0.01 deg.
  const std::string config = f.write(
      "tight.yaml", "calibration: " + kCalibration + "\nestimator:\n  ok_bound_deg: 0.01\n");
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const int rc = command_estimate(
      {"--config", config, "--left", f.left, "--right", f.right, "--seed", "3", "--json"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(rc, kExitRuntimeFailure) << out;
  EXPECT_NE(out.find("\"ok\": false"), std::string::npos) << out;
  EXPECT_NE(out.find("\"not_ok_reason\": \"bound_over_limit\""), std::string::npos) << out;
  EXPECT_NE(err.find("error bound"), std::string::npos) << err;
  EXPECT_NE(err.find("estimator.ok_bound_mm / ok_bound_deg (10 mm / 0.01 deg)"), std::string::npos)
      << err;
  EXPECT_EQ(err.find("partial view"), std::string::npos) << err;
}

template <class Error>
std::string estimate_error_of(const Words& words) {
  ::testing::internal::CaptureStdout();
  std::string message;
  try {
    command_estimate(words);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");  // never a pose from bad input
  return message;
}

TEST(CommandEstimate, BadImagesNameTheFile) {
  const Files f;
  const std::string missing = (f.dir / "nope.png").string();
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", f.config, "--left", missing, "--right", f.right})
          .find(missing + ": cannot read image"),
      std::string::npos);
  const std::string junk = f.write("junk.png", "not a png");
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", f.config, "--left", f.left, "--right", junk})
          .find(junk + ": cannot read image"),
      std::string::npos);
  const std::string small = (f.dir / "small.png").string();
  cv::imwrite(small, cv::Mat(240, 320, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", f.config, "--left", small, "--right", f.right})
          .find(small + ": image is 320x240 but the calibration"),
      std::string::npos);
}

TEST(CommandEstimate, BadCalibrationAndConfigNameTheFileAndKey) {
  const Files f;
  const std::string bad_cal = f.write("cal.yaml", "%YAML:1.0\n---\nimage_size: [640, 480]\n");
  const std::string config = f.write("bad_cal_config.yaml", "calibration: " + bad_cal + "\n");
  EXPECT_EQ(
      estimate_error_of<ConfigError>({"--config", config, "--left", f.left, "--right", f.right}),
      bad_cal + ": missing key 'K1'");
  const std::string unknown =
      f.write("unknown.yaml", "calibration: " + kCalibration + "\nestimator:\n  populaton: 4\n");
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", unknown, "--left", f.left, "--right", f.right})
          .find("estimator.populaton: unknown key"),
      std::string::npos);
  const std::string range = f.write(
      "range.yaml", "calibration: " + kCalibration + "\nestimator:\n  ga:\n    population: 1\n");
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", range, "--left", f.left, "--right", f.right})
          .find("estimator.ga.population: 1 is out of range"),
      std::string::npos);
  const std::string crossed =
      f.write("crossed.yaml",
              "calibration: " + kCalibration + "\nestimator:\n  search:\n    z_min_m: 2.0\n");
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", crossed, "--left", f.left, "--right", f.right})
          .find("estimator.search.z"),
      std::string::npos);
  const std::string no_file = (f.dir / "absent.yaml").string();
  EXPECT_NE(
      estimate_error_of<ConfigError>({"--config", no_file, "--left", f.left, "--right", f.right})
          .find("absent.yaml"),
      std::string::npos);
}

TEST(CommandEstimate, UsageErrors) {
  const Files f;
  EXPECT_NE(estimate_error_of<UsageError>({"--config", f.config, "--left", f.left}).find("--right"),
            std::string::npos);
  EXPECT_NE(estimate_error_of<UsageError>(
                {"--config", f.config, "--left", f.left, "--right", f.right, "--frames", "0"})
                .find("--frames"),
            std::string::npos);
  EXPECT_NE(estimate_error_of<UsageError>({"--bogus"}).find("--bogus"), std::string::npos);
}

}  // namespace
}  // namespace rovctl::app
