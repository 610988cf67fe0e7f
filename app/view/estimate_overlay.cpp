// Silhouettes from the sphere rims of hal/model, the same geometry the estimator's refiner fits.
#include "app/view/estimate_overlay.hpp"

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "hal/model/sphere_rim.hpp"

namespace rovctl::app {
namespace {

constexpr int kRimPoints = 48;

cv::Scalar outline_bgr(hal::ColourClass c) {
  switch (c) {
    case hal::ColourClass::red:
      return {60, 60, 255};
    case hal::ColourClass::green:
      return {80, 255, 80};
    case hal::ColourClass::blue:
      return {255, 160, 60};
    default:
      return {255, 255, 255};
  }
}

}  // namespace

int draw_estimate_overlay(cv::Mat& image_bgr, const hal::CameraModel& camera,
                          const hal::MarkerModel& marker, const Eigen::Isometry3d& T_cam_marker,
                          bool ok) {
  if (!T_cam_marker.matrix().allFinite()) return 0;
  int drawn = 0;
  for (const hal::MarkerSphere& s : marker.spheres) {
    hal::SphereRim rim;
    if (!hal::sphere_rim(T_cam_marker * s.centre_marker_m, s.radius_m, rim)) continue;
    std::array<cv::Point, kRimPoints> points;
    bool in_front = true;
    for (int i = 0; i < kRimPoints; ++i) {
      Eigen::Vector2d uv;
      if (!camera.project(rim.point(2.0 * M_PI * i / kRimPoints), uv) || !uv.allFinite() ||
          std::abs(uv.x()) > 1e5 || std::abs(uv.y()) > 1e5) {
        in_front = false;
        break;
      }
      points[static_cast<std::size_t>(i)] =
          cv::Point(static_cast<int>(std::lround(uv.x())), static_cast<int>(std::lround(uv.y())));
    }
    if (!in_front) continue;
    const cv::Scalar colour = outline_bgr(s.colour);
    if (ok) {
      const cv::Point* outline = points.data();
      cv::polylines(image_bgr, &outline, &kRimPoints, 1, true, colour, 2, cv::LINE_AA);
    } else {
      // A partial view: dashes of three segments with gaps of three, so it reads as untrusted.
      for (int i = 0; i < kRimPoints; i += 6) {
        for (int k = i; k < i + 3; ++k) {
          cv::line(image_bgr, points[static_cast<std::size_t>(k % kRimPoints)],
                   points[static_cast<std::size_t>((k + 1) % kRimPoints)], colour, 2, cv::LINE_AA);
        }
      }
    }
    ++drawn;
  }
  return drawn;
}

}  // namespace rovctl::app
