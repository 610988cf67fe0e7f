// The mock stereo camera renders the world's truth as it was `latency` ago; faults.
#include "hal/mock/mock_stereo_camera.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "sim_test_support.hpp"

namespace rovctl::hal::mock {
namespace {

using std::chrono::milliseconds;

struct CameraFixture : ::testing::Test {
  StereoRig rig = make_parallel_rig(CameraModel{}, 0.178);
  MarkerModel marker = MarkerModel::standard();
  SimParams params = test::still_water_params();
  SimulatedWorld world{params, VehicleGeometry{}, DockingStation{}};

  void start_turning() {
    // 0.6 m short of docked, turning slowly so that every instant looks different.
    Eigen::Isometry3d T = world.docked_T_world_body();
    T.translation().x() -= 0.6;
    VehicleState s;
    s.position_world_m = T.translation();
    s.q_world_body = Eigen::Quaterniond(T.linear());
    s.nu_body(5) = 0.3;
    world.reset(s, Eigen::Vector3d::Zero(), 0);
  }
};

cv::Vec3b pixel_at(const cv::Mat& img, const Eigen::Vector2d& uv) {
  return img.at<cv::Vec3b>(static_cast<int>(std::lround(uv.y())),
                           static_cast<int>(std::lround(uv.x())));
}

TEST_F(CameraFixture, RendersTheTruthFromLatencyAgo) {
  start_turning();
  params.camera.latency_ms = 40.0;
  MockStereoCamera camera(world, rig, marker, params.camera, FaultInjection{}, 11);
  std::string error;
  ASSERT_TRUE(camera.open(error));
  world.step_to(milliseconds(200));
  StereoFrame frame;
  ASSERT_EQ(camera.grab(frame), GrabStatus::ok);
  EXPECT_EQ(frame.left_stamp, milliseconds(160));
  EXPECT_EQ(frame.right_stamp, milliseconds(160));
  const Eigen::Isometry3d truth = camera.last_T_cl_marker_truth();
  EXPECT_TRUE(truth.isApprox(world.T_cl_marker_at(milliseconds(160)), 1e-12));
  EXPECT_FALSE(truth.isApprox(world.truth().T_cl_marker, 1e-4));  // not the present

  // The spheres appear where the true pose projects them, in their colours, in both views.
  const Eigen::Isometry3d T_cr_marker = rig.T_cr_cl * truth;
  for (const MarkerSphere& s : marker.spheres) {
    Eigen::Vector2d uv_l, uv_r;
    ASSERT_TRUE(rig.left.project(truth * s.centre_marker_m, uv_l));
    ASSERT_TRUE(rig.right.project(T_cr_marker * s.centre_marker_m, uv_r));
    const int channel = s.colour == ColourClass::red ? 2 : s.colour == ColourClass::green ? 1 : 0;
    for (const auto& [img, uv] :
         {std::pair{&frame.left_bgr, uv_l}, std::pair{&frame.right_bgr, uv_r}}) {
      const cv::Vec3b px = pixel_at(*img, uv);
      for (int k = 0; k < 3; ++k) {
        if (k != channel) {
          EXPECT_GT(px[channel], px[k] + 30) << s.name;
        }
      }
    }
  }
}

TEST_F(CameraFixture, GrabReusesTheImagesAndNumbersFrames) {
  MockStereoCamera camera(world, rig, marker, params.camera, FaultInjection{}, 11);
  std::string error;
  ASSERT_TRUE(camera.open(error));
  StereoFrame frame;
  ASSERT_EQ(camera.grab(frame), GrabStatus::ok);
  const uchar* left = frame.left_bgr.data;
  const uchar* right = frame.right_bgr.data;
  const cv::Mat first = frame.left_bgr.clone();
  world.step_to(milliseconds(33));
  ASSERT_EQ(camera.grab(frame), GrabStatus::ok);
  EXPECT_EQ(frame.left_bgr.data, left);
  EXPECT_EQ(frame.right_bgr.data, right);
  EXPECT_EQ(frame.sequence, 1u);
  EXPECT_EQ(frame.left_bgr.size(), cv::Size(640, 480));
  EXPECT_GT(cv::norm(first, frame.left_bgr, cv::NORM_L1), 0.0);  // fresh noise
}

TEST_F(CameraFixture, InjectedCameraLossAndDrops) {
  FaultInjection f;
  f.camera_lost_at_s = 0.1;
  MockStereoCamera camera(world, rig, marker, params.camera, f, 11);
  std::string error;
  ASSERT_TRUE(camera.open(error));
  StereoFrame frame;
  EXPECT_EQ(camera.grab(frame), GrabStatus::ok);
  world.step_to(milliseconds(100));
  EXPECT_EQ(camera.grab(frame), GrabStatus::device_lost);
  EXPECT_FALSE(camera.open(error));
  EXPECT_NE(error.find("camera_lost_at_s"), std::string::npos);

  FaultInjection drops;
  drops.camera_timeout_probability = 0.5;
  MockStereoCamera flaky(world, rig, marker, params.camera, drops, 11);
  ASSERT_TRUE(flaky.open(error));
  int timeouts = 0;
  for (int i = 0; i < 40; ++i) timeouts += flaky.grab(frame) == GrabStatus::timeout ? 1 : 0;
  EXPECT_GT(timeouts, 5);
  EXPECT_LT(timeouts, 35);
}

// The left image of the frame at 200 ms of a turning vehicle, exposed for `exposure_ms` (0: sharp).
template <class Fixture>
cv::Mat turning_frame(Fixture& f, double exposure_ms, std::chrono::nanoseconds& exposure) {
  f.start_turning();
  CameraSimParams p = f.params.camera;
  p.exposure_ms = exposure_ms;
  MockStereoCamera camera(f.world, f.rig, f.marker, p, FaultInjection{}, 11);
  std::string error;
  EXPECT_TRUE(camera.open(error));
  f.world.step_to(milliseconds(200));
  StereoFrame frame;
  EXPECT_EQ(camera.grab(frame), GrabStatus::ok);
  exposure = frame.exposure;
  return frame.left_bgr.clone();
}

int pixels_changed(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff, grey;
  cv::absdiff(a, b, diff);
  cv::Mat channels[3];
  cv::split(diff, channels);
  grey = cv::max(channels[0], cv::max(channels[1], channels[2]));
  return cv::countNonZero(grey > 20);
}

TEST_F(CameraFixture, AManualExposureSmearsByItsLengthAndTheFrameCarriesIt) {
  std::chrono::nanoseconds exposure{};
  const cv::Mat sharp = turning_frame(*this, 0.0, exposure);
  EXPECT_FALSE(StereoFrame{}.exposure_known());
  EXPECT_EQ(exposure.count(), 0);  // sharp: no exposure the frame could claim
  // 0.3 rad/s of yaw: under a pixel through 0.5 ms, a streak of several through 30 ms.
  const cv::Mat short_exposure = turning_frame(*this, 0.5, exposure);
  EXPECT_EQ(exposure, std::chrono::microseconds(500));
  EXPECT_EQ(pixels_changed(sharp, short_exposure), 0);
  const cv::Mat long_exposure = turning_frame(*this, 30.0, exposure);
  EXPECT_EQ(exposure, milliseconds(30));
  const cv::Mat longer_exposure = turning_frame(*this, 60.0, exposure);
  const int smeared = pixels_changed(sharp, long_exposure);
  EXPECT_GT(smeared, 50);
  EXPECT_GT(pixels_changed(sharp, longer_exposure), smeared);
}

SimParams exposure_scenario_params() {
  SimParams p = test::still_water_params();
  p.scenario = "exposure";
  return p;
}

struct ExposureScenarioFixture : CameraFixture {
  SimParams exposure_params = exposure_scenario_params();
  SimulatedWorld exposure_world{exposure_params, VehicleGeometry{}, DockingStation{}};
};

TEST_F(ExposureScenarioFixture, SmearsItsAutoExposureWithoutTellingTheFrame) {
  std::chrono::nanoseconds exposure{};
  MockStereoCamera auto_camera(exposure_world, rig, marker, params.camera, FaultInjection{}, 11);
  EXPECT_EQ(auto_camera.exposure(), milliseconds(33));
  EXPECT_FALSE(auto_camera.exposure_known());
  CameraSimParams manual = params.camera;
  manual.exposure_ms = 4.0;
  MockStereoCamera capped(exposure_world, rig, marker, manual, FaultInjection{}, 11);
  EXPECT_EQ(capped.exposure(), milliseconds(4));
  EXPECT_TRUE(capped.exposure_known());
  std::string error;
  ASSERT_TRUE(auto_camera.open(error));
  ASSERT_TRUE(capped.open(error));
  exposure_world.step_to(milliseconds(200));
  StereoFrame a, c;
  ASSERT_EQ(auto_camera.grab(a), GrabStatus::ok);
  ASSERT_EQ(capped.grab(c), GrabStatus::ok);
  EXPECT_EQ(a.exposure.count(), 0);
  EXPECT_EQ(c.exposure, milliseconds(4));
  // The same vibrating mount: the truth turns with it, the same in both.
  EXPECT_TRUE(auto_camera.last_T_cl_marker_truth().isApprox(capped.last_T_cl_marker_truth()));
  EXPECT_FALSE(auto_camera.last_T_cl_marker_truth().isApprox(
      exposure_world.T_cl_marker_at(milliseconds(160)), 1e-6));
  (void)exposure;
}

}  // namespace
}  // namespace rovctl::hal::mock
