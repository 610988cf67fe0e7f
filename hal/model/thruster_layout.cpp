// BlueROV2 Heavy geometry and the thrust configuration matrix.
#include "hal/model/thruster_layout.hpp"

#include <cmath>

namespace rovctl::hal {

ThrusterLayout ThrusterLayout::bluerov2_heavy() {
  ThrusterLayout l;
  const double c = std::sqrt(0.5);
  // Horizontal thrusters 1-4 (vectored, in the x-y plane), vertical 5-8 (pushing along +z, down).
  // Directions follow ArduSub's vectored-6DOF factors so that a + command on all four horizontal
  // thrusters with their factor signs yields pure surge.
  const struct {
    const char* name;
    Eigen::Vector3d r;
    Eigen::Vector3d d;
  } spec[] = {
      {"t1_front_right", {0.156, 0.111, 0.085}, {c, -c, 0}},
      {"t2_front_left", {0.156, -0.111, 0.085}, {c, c, 0}},
      {"t3_rear_right", {-0.156, 0.111, 0.085}, {c, c, 0}},
      {"t4_rear_left", {-0.156, -0.111, 0.085}, {c, -c, 0}},
      {"t5_vert_front_right", {0.120, 0.218, 0.0}, {0, 0, 1}},
      {"t6_vert_front_left", {0.120, -0.218, 0.0}, {0, 0, 1}},
      {"t7_vert_rear_right", {-0.120, 0.218, 0.0}, {0, 0, 1}},
      {"t8_vert_rear_left", {-0.120, -0.218, 0.0}, {0, 0, 1}},
  };
  int channel = 0;
  for (const auto& s : spec) {
    Thruster t;
    t.name = s.name;
    t.position_body_m = s.r;
    t.direction_body = s.d.normalized();
    t.channel = channel++;
    l.thrusters.push_back(t);
  }
  return l;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> ThrusterLayout::configuration_matrix() const {
  Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, static_cast<Eigen::Index>(thrusters.size()));
  for (std::size_t i = 0; i < thrusters.size(); ++i) {
    const Thruster& t = thrusters[i];
    const Eigen::Vector3d d = t.direction_body.normalized();
    B.col(static_cast<Eigen::Index>(i)) << d, t.position_body_m.cross(d);
  }
  return B;
}

void describe(ParamVisitor& v, ThrusterLayout& layout) {
  param_list(
      v, "thrusters", "the vehicle's thrusters (default: BlueROV2 Heavy)", layout.thrusters, 1, 8,
      [](ParamVisitor& e, Thruster& t) {
        e.param("name", t.name, "thruster name (for logs and the motor test)", {}, true);
        e.param("position_m", t.position_body_m,
                {"m", -5.0, 5.0, "thruster position in the body frame", true});
        e.param("direction", t.direction_body,
                {"-", -1.0, 1.0, "thrust axis for a positive command, body frame", true});
        e.param("max_forward_n", t.max_forward_n, {"N", 0.1, 1000.0, "thrust at command +1"});
        e.param("max_reverse_n", t.max_reverse_n,
                {"N", 0.1, 1000.0, "thrust magnitude at command -1"});
        e.param("channel", t.channel, {"-", 0, 7, "index on the thruster bus", true});
      });
}

}  // namespace rovctl::hal
