// The vehicle's thrusters: where they are, which way they push, how hard. What the vehicle is;
// how a wrench is shared among them lives in control/ (allocation).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal {

struct Thruster {
  std::string name;
  Eigen::Vector3d position_body_m = Eigen::Vector3d::Zero();  // body: x fwd, y stbd, z down
  Eigen::Vector3d direction_body = Eigen::Vector3d::UnitX();  // unit thrust axis for a + command
  double max_forward_n = 51.5;                                // thrust at command +1
  double max_reverse_n = 40.2;                                // thrust magnitude at command -1
  int channel = 0;  // index on the thruster bus (Modbus register, ESC index)
};

struct ThrusterLayout {
  std::vector<Thruster> thrusters;

  // BlueROV2 Heavy (ArduSub "vectored 6DOF" frame): four horizontal thrusters at 45 degrees and
  // four vertical ones. Positions from von Benzon et al., "An Open-Source Benchmark Simulator:
  // Control of a BlueROV2 Underwater Robot", J. Mar. Sci. Eng. 10(12), 2022, Table 2; T200
  // thrust at 16 V from Blue Robotics' published performance chart (5.25 kgf fwd, 4.1 kgf rev).
  static ThrusterLayout bluerov2_heavy();

  // The 6 x n thrust configuration matrix at unit forward thrust: column i is thruster i's
  // [force; moment about the body origin] per newton.
  Eigen::Matrix<double, 6, Eigen::Dynamic> configuration_matrix() const;
};

void describe(ParamVisitor& v, ThrusterLayout& layout);

}  // namespace rovctl::hal
