// Light through turbid water: each colour channel is attenuated with the distance it travels
// and replaced by the veil of light the water scatters back into the camera along the same ray.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// Coastal water. The coefficients follow Jerlov's coastal water types (N. G. Jerlov, Marine
// Optics, Elsevier 1976; their absorption and scattering per type: M. G. Solonenko and
// C. D. Mobley, Appl. Opt. 54(17), 5392, 2015; in camera RGB bands: D. Akkaynak et al., "What is
// the space of attenuation coefficients in underwater computer vision?", CVPR 2017): water itself
// absorbs red, dissolved organic matter and chlorophyll absorb blue, so green carries farthest.
// The defaults sit inside the coastal range (c_R 0.6-1.2, c_G 0.25-0.5, c_B 0.3-0.6 /m); they
// are representative values, not one table's entries.
struct TurbidWater {
  Eigen::Vector3d attenuation_rgb_per_m{0.9, 0.38, 0.45};
  // The backscattered light at infinite range (B_inf), linear RGB: the colour of the water.
  Eigen::Vector3d veil_rgb{0.10, 0.30, 0.25};
  // The background (station face, sea floor) is a plane this far behind the marker, parallel to
  // it; rays that miss it see open water this deep.
  double background_behind_marker_m = 0.5;
  double open_water_m = 8.0;
};

void describe(ParamVisitor& v, TurbidWater& w);

class WaterOptics {
 public:
  explicit WaterOptics(const TurbidWater& water);

  // What the camera sees of a surface of linear colour `rgb` at `distance_m` along its ray:
  // J exp(-c d) + B_inf (1 - exp(-c d)), per channel (Akkaynak and Treibitz, "A Revised
  // Underwater Image Formation Model", CVPR 2018, with one coefficient for both terms). Only
  // the path to the camera: the light falling on the surface is the scene's, as in clear water.
  Eigen::Vector3f through(const Eigen::Vector3f& rgb, float distance_m) const;

  // Fills out_bgr (CV_8UC3, sized) with the background seen through the water: `row_rgb[v]` is
  // the background's own linear colour on image row v, `rays` the unit-z ray of every pixel and
  // `to_srgb8` the 4096-step linear-to-sRGB table. No heap allocation.
  void draw_background(const Eigen::Isometry3d& T_cam_marker, const Eigen::Vector3f* rays,
                       const Eigen::Vector3f* row_rgb, const std::uint8_t* to_srgb8,
                       cv::Mat& out_bgr) const;

 private:
  static constexpr int kSteps = 2048;  // transmittance table over [0, open_water_m]

  TurbidWater water_;
  Eigen::Vector3f c_per_m_;
  Eigen::Vector3f veil_;
  float step_m_ = 0.0f;
  std::array<Eigen::Vector3f, kSteps> transmittance_;
};

}  // namespace rovctl::hal::mock
