// error_bound: the 99 % quantile of an error's norm against chi-square tables and against a
// sampled Gaussian of a long, tilted covariance (a rim fit's shape).
#include "estimator/error_bound.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

using rovctl::estimator::error_bound_99;
using rovctl::estimator::norm_quantile_99;

TEST(ErrorBound, OneAxisIsTheNormalQuantile) {
  // |e| = |x|, x ~ N(0, 2 mm): P(|x| <= 2.5758 sigma) = 0.99.
  const Eigen::Matrix3d C = Eigen::Vector3d(4e-6, 0.0, 0.0).asDiagonal();
  EXPECT_NEAR(norm_quantile_99(C), 2.5758 * 0.002, 0.01 * 2.5758 * 0.002);
}

TEST(ErrorBound, ThreeEqualAxesAreTheChiSquareQuantile) {
  // chi-square(3)'s 99 % quantile is 11.345.
  const Eigen::Matrix3d C = 0.5 * Eigen::Matrix3d::Identity();
  EXPECT_NEAR(norm_quantile_99(C), std::sqrt(11.345 * 0.5), 0.005 * std::sqrt(11.345 * 0.5));
}

TEST(ErrorBound, MatchesASampledLongTiltedCovariance) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d sigma(3.0, 1.0, 0.4);
  const Eigen::Matrix3d C = R * sigma.cwiseAbs2().asDiagonal() * R.transpose();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  std::vector<double> norms(200000);
  for (double& v : norms) {
    const Eigen::Vector3d e = R * sigma.cwiseProduct(Eigen::Vector3d(n01(rng), n01(rng), n01(rng)));
    v = e.norm();
  }
  std::nth_element(norms.begin(), norms.begin() + 198000, norms.end());
  const double sampled = norms[198000];
  EXPECT_NEAR(norm_quantile_99(C), sampled, 0.02 * sampled);
  // And tighter than the trace's three sigma, which such a shape over-states.
  EXPECT_LT(norm_quantile_99(C), 0.95 * 3.0 * std::sqrt(C.trace()));
}

TEST(ErrorBound, NoVarianceIsNoErrorAndNaNSaysSo) {
  EXPECT_EQ(norm_quantile_99(Eigen::Matrix3d::Zero()), 0.0);
  Eigen::Matrix3d C = Eigen::Matrix3d::Identity();
  C(1, 1) = std::nan("");
  EXPECT_TRUE(std::isnan(norm_quantile_99(C)));
}

TEST(ErrorBound, RotationInDegreesAndTranslationInMetres) {
  Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Zero();
  cov(0, 0) = std::pow(M_PI / 180.0, 2);  // 1 deg sigma about x
  cov(5, 5) = 1e-6;                       // 1 mm sigma in depth
  const auto b = error_bound_99(cov);
  EXPECT_NEAR(b.deg, 2.5758, 0.03);
  EXPECT_NEAR(b.m, 0.0025758, 3e-5);
}

TEST(ErrorBound, TheTracesThreeSigmaIsTheLooserBound) {
  Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Zero();
  cov.diagonal() << 1e-4, 1e-4, 1e-4, 4e-6, 0.0, 0.0;
  const auto q = rovctl::estimator::error_bound_99(cov);
  const auto t = rovctl::estimator::error_bound_3_sigma(cov);
  EXPECT_NEAR(t.deg / q.deg, 3.0 * std::sqrt(3.0) / 3.368, 0.01);  // three equal axes
  EXPECT_NEAR(t.m / q.m, 3.0 / 2.5758, 0.01);                      // one axis
}

TEST(ErrorBound, AnotherFitIsAsGoodOnlyWithinTheChiSquareQuantile) {
  using rovctl::estimator::fits_as_well;
  EXPECT_TRUE(fits_as_well(48.0, 30.0));         // fits better
  EXPECT_TRUE(fits_as_well(48.0, 48.0 + 6.6));   // worse by less than 6.63
  EXPECT_FALSE(fits_as_well(48.0, 48.0 + 6.7));  // worse by more
}

}  // namespace
