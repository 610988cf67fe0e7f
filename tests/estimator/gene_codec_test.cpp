// The 72-bit gene: round trip to within one step, clamping at the volume, two-point crossover.
#include "estimator/gene_codec.hpp"

#include <gtest/gtest.h>

#include "hal/model/pose.hpp"

namespace rovctl::estimator {
namespace {

TEST(GeneCodec, RoundTripWithinOneStep) {
  const GeneCodec codec{SearchVolume{}};
  const Eigen::Isometry3d T = hal::make_pose(
      {0.123, -0.045, 0.678},
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, -1).normalized())));
  Gene g;
  ASSERT_TRUE(codec.encode(T, g));
  const Eigen::Isometry3d back = codec.decode(g);
  EXPECT_LT((back.translation() - T.translation()).norm(), 0.5e-3);
  EXPECT_LT(hal::rotation_angle_rad(back.linear(), T.linear()), 1e-3);
  Gene again;
  codec.encode(back, again);
  EXPECT_EQ(again, g);
  EXPECT_NEAR(codec.resolution(0), 0.8 / 4095, 1e-12);
}

TEST(GeneCodec, OutsideTheVolumeIsClampedAndReported) {
  const GeneCodec codec{SearchVolume{}};
  Gene g;
  EXPECT_FALSE(codec.encode(hal::make_pose({0.0, 0.0, 3.0}, Eigen::Quaterniond::Identity()), g));
  EXPECT_EQ(g.field[2], kFieldMax);
  EXPECT_FALSE(codec.encode(hal::make_pose({0.0, 0.0, 0.5}, Eigen::Quaterniond(Eigen::AngleAxisd(
                                                                2.5, Eigen::Vector3d::UnitX()))),
                            g));
}

TEST(GeneCodec, EveryGeneDecodesToARotation) {
  SearchVolume v;
  v.epsilon_max = 1.0;
  const GeneCodec codec(v);
  Gene g;
  g.field = {0, kFieldMax, 100, kFieldMax, kFieldMax, kFieldMax};  // |e| > 1
  const Eigen::Matrix3d R = codec.decode(g).linear();
  EXPECT_LT((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
}

TEST(GeneCodec, TwoPointCrossoverSwapsTheBitsBetweenTheCuts) {
  Gene a, b, ca, cb;
  a.field.fill(0);
  b.field.fill(kFieldMax);
  two_point_crossover(a, b, 10, 30, ca, cb);
  for (int bit = 0; bit < kGeneBits; ++bit) {
    const bool from_b = bit >= 10 && bit < 30;
    const bool set = (ca.field[bit / kBitsPerField] >> (bit % kBitsPerField)) & 1u;
    EXPECT_EQ(set, from_b) << bit;
    const bool set_b = (cb.field[bit / kBitsPerField] >> (bit % kBitsPerField)) & 1u;
    EXPECT_EQ(set_b, !from_b) << bit;
  }
  two_point_crossover(a, b, 0, kGeneBits, ca, cb);
  EXPECT_EQ(ca, b);
  EXPECT_EQ(cb, a);
  flip_bit(ca, 13);
  EXPECT_EQ(ca.field[1], kFieldMax ^ 2u);
}

}  // namespace
}  // namespace rovctl::estimator
