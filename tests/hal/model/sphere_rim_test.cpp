// sphere_rim: every rim point is tangent to the sphere (the ray from the camera touches it there),
// and spheres around or behind the camera have no rim.
#include "hal/model/sphere_rim.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rovctl::hal {
namespace {

TEST(SphereRim, RimPointsAreTangentToTheSphere) {
  const Eigen::Vector3d c(0.1, -0.05, 0.6);
  const double r = 0.02;
  SphereRim rim;
  ASSERT_TRUE(sphere_rim(c, r, rim));
  EXPECT_NEAR(rim.e1.dot(rim.e2), 0.0, 1e-12);
  EXPECT_NEAR(rim.e1.dot(c), 0.0, 1e-12);
  for (int k = 0; k < 16; ++k) {
    const Eigen::Vector3d p = rim.point(2.0 * M_PI * k / 16);
    EXPECT_NEAR((p - c).norm(), r, 1e-12) << "on the sphere";
    EXPECT_NEAR(p.dot(p - c), 0.0, 1e-12) << "the viewing ray is perpendicular to the radius";
  }
}

TEST(SphereRim, NoRimInsideOrBehind) {
  SphereRim rim;
  EXPECT_FALSE(sphere_rim(Eigen::Vector3d(0.0, 0.0, 0.01), 0.02, rim));
  EXPECT_FALSE(sphere_rim(Eigen::Vector3d(0.0, 0.0, -0.5), 0.02, rim));
}

}  // namespace
}  // namespace rovctl::hal
