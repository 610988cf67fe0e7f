// Shared fixture for estimator tests: the shipped (distorted, toe-in) calibration, the standard
// marker, renderers and seeded random marker poses in view of both cameras.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>

#include "estimator/stereo_calibration.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/pose.hpp"

namespace rovctl::estimator::testing {

inline std::string shipped_calibration_path() {
  return std::string(ROVCTL_TEST_DATA_DIR) + "/../../deploy/config/stereo_calibration.yaml";
}

struct TestScene {
  hal::StereoRig rig = load_stereo_calibration(shipped_calibration_path());
  hal::MarkerModel marker = hal::MarkerModel::standard();
  hal::mock::RenderOptions options;
  hal::mock::SceneRenderer left{rig.left, marker, options};
  hal::mock::SceneRenderer right{rig.right, marker, options};
  cv::Mat left_bgr, right_bgr;

  TestScene() = default;
  explicit TestScene(const hal::mock::RenderOptions& o)
      : options(o), left(rig.left, marker, o), right(rig.right, marker, o) {}

  void render(const Eigen::Isometry3d& T_cl_marker, std::uint64_t seed = 1) {
    hal::mock::render_stereo(left, right, rig, T_cl_marker, seed, left_bgr, right_bgr);
  }

  // Paints sphere s out of both rendered views in the water's colour (a sphere behind a bar).
  void hide_sphere(const Eigen::Isometry3d& T_cl_marker, int s) {
    for (int v = 0; v < 2; ++v) {
      const hal::CameraModel& camera = v == 0 ? rig.left : rig.right;
      const Eigen::Isometry3d T_cam_cl = v == 0 ? Eigen::Isometry3d::Identity() : rig.T_cr_cl;
      Eigen::Vector2d uv;
      if (!camera.project(T_cam_cl * T_cl_marker * marker.spheres[s].centre_marker_m, uv)) continue;
      cv::circle(v == 0 ? left_bgr : right_bgr,
                 cv::Point(static_cast<int>(uv.x()), static_cast<int>(uv.y())), 40,
                 cv::Scalar(90, 70, 40), cv::FILLED);
    }
  }

  // An image of plain water, no marker: a pair of them is a frame nothing can be confirmed in.
  cv::Mat empty_image() const {
    return cv::Mat(rig.left.height_px, rig.left.width_px, CV_8UC3, cv::Scalar(90, 70, 40));
  }
};

// A marker pose z_min..z_max ahead, in view of both cameras, turned up to max_angle_deg.
inline Eigen::Isometry3d random_pose(std::mt19937_64& rng, double z_min = 0.3, double z_max = 0.7,
                                     double max_angle_deg = 25.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double z = z_min + (z_max - z_min) * 0.5 * (u(rng) + 1.0);
  const Eigen::Vector3d t(0.05 + z * 0.12 * u(rng), z * 0.08 * u(rng), z);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  const double angle = max_angle_deg * M_PI / 180.0 * 0.5 * (u(rng) + 1.0);
  return hal::make_pose(t, Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)));
}

inline double translation_error_mm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm() * 1000.0;
}
inline double rotation_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return hal::rotation_angle_rad(a.linear(), b.linear()) * 180.0 / M_PI;
}

}  // namespace rovctl::estimator::testing
