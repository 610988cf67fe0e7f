// The estimate drawn on an image: where the camera model puts the spheres, nothing when the pose
// is unknown or behind the camera.
#include "app/view/estimate_overlay.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace rovctl::app {
namespace {

TEST(EstimateOverlay, DrawsEachSphereWhereTheCameraSeesIt) {
  const hal::CameraModel camera;
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  cv::Mat image(camera.height_px, camera.width_px, CV_8UC3, cv::Scalar::all(0));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.0, 0.0, 0.5);
  EXPECT_EQ(draw_estimate_overlay(image, camera, marker, T, true), 3);
  for (const hal::MarkerSphere& s : marker.spheres) {
    Eigen::Vector2d centre;
    ASSERT_TRUE(camera.project(T * s.centre_marker_m, centre));
    const double r_px = camera.fx_px * s.radius_m / (T * s.centre_marker_m).z();
    // The outline passes about r_px right of the centre; the centre itself stays dark.
    const cv::Rect ring(static_cast<int>(centre.x() + r_px) - 3, static_cast<int>(centre.y()) - 3,
                        7, 7);
    EXPECT_GT(cv::countNonZero(image(ring).reshape(1) > 0), 0) << s.name;
    EXPECT_EQ(image.at<cv::Vec3b>(static_cast<int>(centre.y()), static_cast<int>(centre.x())),
              cv::Vec3b(0, 0, 0))
        << s.name;
  }
}

TEST(EstimateOverlay, APartialViewIsDrawnDashed) {
  const hal::CameraModel camera;
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.0, 0.0, 0.5);
  cv::Mat solid(camera.height_px, camera.width_px, CV_8UC3, cv::Scalar::all(0));
  cv::Mat dashed = solid.clone();
  draw_estimate_overlay(solid, camera, marker, T, true);
  draw_estimate_overlay(dashed, camera, marker, T, false);
  // Every dashed pixel lies on the solid outline, and about half of the outline is left out.
  cv::Mat grey_solid, grey_dashed;
  cv::cvtColor(solid, grey_solid, cv::COLOR_BGR2GRAY);
  cv::cvtColor(dashed, grey_dashed, cv::COLOR_BGR2GRAY);
  const int solid_px = cv::countNonZero(grey_solid > 0);
  const int dashed_px = cv::countNonZero(grey_dashed > 0);
  EXPECT_GT(dashed_px, solid_px / 4);
  EXPECT_LT(dashed_px, solid_px * 3 / 4);
}

TEST(EstimateOverlay, NothingForAnUnknownPoseOrOneBehindTheCamera) {
  const hal::CameraModel camera;
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  cv::Mat image(camera.height_px, camera.width_px, CV_8UC3, cv::Scalar::all(0));
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(draw_estimate_overlay(image, camera, marker, nan, true), 0);
  Eigen::Isometry3d behind = Eigen::Isometry3d::Identity();
  behind.translation() = Eigen::Vector3d(0.0, 0.0, -0.5);
  EXPECT_EQ(draw_estimate_overlay(image, camera, marker, behind, true), 0);
  EXPECT_EQ(cv::countNonZero(image.reshape(1)), 0);
}

}  // namespace
}  // namespace rovctl::app
