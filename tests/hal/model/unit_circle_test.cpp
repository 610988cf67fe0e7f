// The fixed-angle table matches the angles it stands for, including a start offset.
#include "hal/model/unit_circle.hpp"

#include <gtest/gtest.h>

#include "hal/model/sphere_rim.hpp"

namespace rovctl::hal {
namespace {

TEST(UnitCircle, PointKIsAtTwoPiKOverNFromTheStart) {
  const UnitCircle<48> around(-M_PI);
  for (int k = 0; k < 48; ++k) {
    const double phi = 2.0 * M_PI * k / 48 - M_PI;
    EXPECT_DOUBLE_EQ(around[k].x(), std::cos(phi)) << k;
    EXPECT_DOUBLE_EQ(around[k].y(), std::sin(phi)) << k;
  }
  EXPECT_NEAR(around[12].x(), 0.0, 1e-15);  // -pi/2: straight down the y axis
  EXPECT_NEAR(around[12].y(), -1.0, 1e-15);
}

TEST(UnitCircle, RimPointFromTheTableIsTheRimPointAtThatAngle) {
  SphereRim rim;
  rim.centre_m = {0.1, -0.2, 1.0};
  rim.radius_m = 0.02;
  const UnitCircle<32> around;
  for (int k = 0; k < 32; ++k) {
    const Eigen::Vector3d a = rim.point(2.0 * M_PI * k / 32);
    EXPECT_LT((rim.point(around[k].x(), around[k].y()) - a).norm(), 1e-15) << k;
  }
}

}  // namespace
}  // namespace rovctl::hal
