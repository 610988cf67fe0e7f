// Default marker geometry and its parameter declarations.
#include "hal/model/marker_model.hpp"

namespace rovctl::hal {

const char* to_string(ColourClass c) {
  switch (c) {
    case ColourClass::red:
      return "red";
    case ColourClass::green:
      return "green";
    case ColourClass::blue:
      return "blue";
    default:
      return "none";
  }
}

MarkerModel MarkerModel::standard() {
  MarkerModel m;
  MarkerSphere red;
  red.name = "red";
  red.colour = ColourClass::red;
  red.centre_marker_m = {-0.060, 0.030, 0.0};
  red.hue_min_deg = 335.0;
  red.hue_max_deg = 25.0;
  red.albedo_rgb = {0.85, 0.08, 0.06};
  // Water takes red first: a metre of coastal water leaves a red sphere at saturation 0.2-0.3
  // (hue still red), below the other colours' floor. Measured on the POV-Ray water set.
  red.saturation_min = 0.2;
  MarkerSphere green;
  green.name = "green";
  green.colour = ColourClass::green;
  green.centre_marker_m = {0.060, 0.030, 0.0};
  green.hue_min_deg = 85.0;
  green.hue_max_deg = 160.0;
  green.albedo_rgb = {0.08, 0.75, 0.12};
  MarkerSphere blue;
  blue.name = "blue";
  blue.colour = ColourClass::blue;
  blue.centre_marker_m = {0.0, -0.060, -0.040};
  blue.hue_min_deg = 205.0;
  blue.hue_max_deg = 260.0;
  blue.albedo_rgb = {0.06, 0.12, 0.85};
  m.spheres = {red, green, blue};
  return m;
}

void describe(ParamVisitor& v, MarkerModel& marker) {
  param_list(
      v, "spheres", "the marker's spheres (exactly one per colour class)", marker.spheres, 1, 3,
      [](ParamVisitor& e, MarkerSphere& s) {
        const std::string before = s.name;
        e.param("name", s.name, "sphere name, also its colour class", {"red", "green", "blue"},
                true);
        if (s.name != before) {
          // A new element starts from the standard sphere of its colour, so a config
          // need only give what differs.
          for (const MarkerSphere& standard : MarkerModel::standard().spheres) {
            if (standard.name == s.name) s = standard;
          }
        }
        e.param("centre_m", s.centre_marker_m,
                {"m", -1.0, 1.0, "sphere centre in the marker frame", true});
        e.param("radius_m", s.radius_m, {"m", 0.002, 0.5, "sphere radius"});
        e.param("hue_min_deg", s.hue_min_deg,
                {"deg", 0.0, 360.0, "lower end of the hue window (wraps through 0)"});
        e.param("hue_max_deg", s.hue_max_deg, {"deg", 0.0, 360.0, "upper end of the hue window"});
        e.param("saturation_min", s.saturation_min,
                {"-", 0.0, 1.0, "saturation floor for this colour"});
        e.param("value_min", s.value_min, {"-", 0.0, 1.0, "value (brightness) floor"});
        e.param("albedo_rgb", s.albedo_rgb,
                {"-", 0.0, 1.0, "surface colour for the simulated cameras, linear RGB"});
      });
}

}  // namespace rovctl::hal
