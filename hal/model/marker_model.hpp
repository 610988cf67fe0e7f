// The docking marker: three coloured spheres fixed in the marker frame. What the marker is;
// how it is found lives in estimator/.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal {

// Class labels of the segmented image. 0 is background; the values index lookup tables.
enum class ColourClass : std::uint8_t { none = 0, red = 1, green = 2, blue = 3 };
constexpr int kColourClassCount = 4;

const char* to_string(ColourClass c);

struct MarkerSphere {
  std::string name;  // "red", "green" or "blue": also selects the colour class
  ColourClass colour = ColourClass::red;
  // Marker frame: x right, y down, z into the station (parallel to the camera when aligned).
  Eigen::Vector3d centre_marker_m = Eigen::Vector3d::Zero();
  double radius_m = 0.020;
  // Segmentation of this sphere's colour: hue window in degrees [0, 360) (min > max wraps
  // through 0), with saturation and value floors in [0, 1].
  double hue_min_deg = 0.0;
  double hue_max_deg = 20.0;
  double saturation_min = 0.35;
  double value_min = 0.12;
  // Surface colour for the renderer, linear RGB in [0, 1].
  Eigen::Vector3d albedo_rgb = Eigen::Vector3d(0.9, 0.1, 0.1);
};

struct MarkerModel {
  std::vector<MarkerSphere> spheres;

  // The default marker: red, green and blue 40 mm spheres on a 120 x 90 mm triangle, the blue
  // one 40 mm proud of the others so that no two poses look alike.
  static MarkerModel standard();
};

void describe(ParamVisitor& v, MarkerModel& marker);

}  // namespace rovctl::hal
