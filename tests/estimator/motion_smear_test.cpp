// motion_smear: the view's smear is one two blobs agree on, in direction and length, either way
// along the line; a lone elongated blob is no smear.
#include "estimator/motion_smear.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace rovctl::estimator;
using Smears = std::array<BlobSmear, rovctl::hal::kColourClassCount>;

BlobSmear at_deg(double length_px, double angle_deg, double width_px) {
  const double a = angle_deg * M_PI / 180.0;
  return {length_px * std::cos(a), length_px * std::sin(a), width_px};
}

TEST(MotionSmear, TwoBlobsAgreeingMakeTheViewsSmearTheLongerOfThem) {
  Smears s{};
  s[1] = at_deg(30.0, 10.0, 18.0);
  s[2] = at_deg(26.0, 15.0, 20.0);
  const SharedSmear m = shared_smear(s);
  ASSERT_TRUE(m.valid);
  EXPECT_DOUBLE_EQ(m.u_px, s[1].u_px);
  EXPECT_DOUBLE_EQ(m.v_px, s[1].v_px);
  EXPECT_DOUBLE_EQ(m.min_length_px, 26.0);
  EXPECT_DOUBLE_EQ(m.min_width_px, 18.0);
  EXPECT_DOUBLE_EQ(m.max_width_px, 20.0);
}

TEST(MotionSmear, ALoneElongatedBlobIsNoSmear) {
  Smears s{};
  s[2] = at_deg(30.0, 10.0, 18.0);
  EXPECT_FALSE(shared_smear(s).valid);
  // Beside a sharp disc's reading (a pixel or two, any way).
  s[1] = at_deg(1.5, 80.0, 18.0);
  s[3] = at_deg(2.0, -40.0, 18.0);
  EXPECT_FALSE(shared_smear(s).valid);
}

TEST(MotionSmear, DirectionIsSignFreeButMustAgree) {
  Smears s{};
  s[1] = at_deg(30.0, 10.0, 18.0);
  s[2] = at_deg(30.0, 190.0 + kSmearAgreeDeg - 1.0, 18.0);  // the same line, read the other way
  EXPECT_TRUE(shared_smear(s).valid);
  s[2] = at_deg(30.0, 10.0 + kSmearAgreeDeg + 1.0, 18.0);
  EXPECT_FALSE(shared_smear(s).valid);
}

TEST(MotionSmear, LengthsMustAgree) {
  Smears s{};
  s[1] = at_deg(30.0, 0.0, 18.0);
  s[2] = at_deg(30.0 * kSmearAgreeLength + 0.5, 0.0, 18.0);
  EXPECT_TRUE(shared_smear(s).valid);
  s[2] = at_deg(30.0 * kSmearAgreeLength - 0.5, 0.0, 18.0);
  EXPECT_FALSE(shared_smear(s).valid);
}

TEST(MotionSmear, ADimBlobMeasuredShortStaysOutOfTheAgreeingSet) {
  // Red at range is labelled in its smear's core only: short, and narrow.
  Smears s{};
  s[1] = at_deg(7.0, -40.0, 13.0);
  s[2] = at_deg(19.9, 82.0, 20.8);
  s[3] = at_deg(24.0, 85.0, 21.2);
  const SharedSmear m = shared_smear(s);
  ASSERT_TRUE(m.valid);
  EXPECT_DOUBLE_EQ(m.u_px, s[3].u_px);
  EXPECT_DOUBLE_EQ(m.min_length_px, 19.9);
  EXPECT_DOUBLE_EQ(m.min_width_px, 20.8);
}

TEST(MotionSmear, ASharpSphereAsWideAsTheElongatedOnesSaysTheCameraDidNotMove) {
  // Measured in the sim: a bar passing two spheres, the third round and whole beside them.
  Smears s{};
  s[1] = at_deg(33.2, -2.4, 26.0);
  s[2] = at_deg(2.5, 0.0, 27.4);
  s[3] = at_deg(38.0, -3.0, 33.7);
  EXPECT_FALSE(shared_smear(s).valid);
  // The same pair beside a dim sphere's narrow core is smeared ...
  s[2] = at_deg(2.5, 0.0, kSmearVetoWidth * 26.0 - 0.5);
  EXPECT_TRUE(shared_smear(s).valid);
  // ... and beside one as wide but smeared, only shorter (red, dimmer, in the mock's render).
  s[2] = at_deg(kSmearVetoLength * 33.2 + 0.5, 0.0, 27.4);
  EXPECT_TRUE(shared_smear(s).valid);
}

TEST(MotionSmear, TheLargestAgreeingSetWins) {
  Smears s{};
  s[1] = at_deg(40.0, 60.0, 15.0);  // longest, but alone (and narrower)
  s[2] = at_deg(25.0, 0.0, 18.0);
  s[3] = at_deg(24.0, 5.0, 19.0);
  const SharedSmear m = shared_smear(s);
  ASSERT_TRUE(m.valid);
  EXPECT_DOUBLE_EQ(m.u_px, s[2].u_px);
  EXPECT_DOUBLE_EQ(m.min_length_px, 24.0);
}

}  // namespace
