// RateFilter: converges to the true slope, attenuates noise that a raw difference passes,
// primes on the first sample, ignores non-positive time steps.
#include "control/rate_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace rovctl::control {
namespace {

using V = RateFilter::Vector;

TEST(RateFilter, FirstSamplePrimesWithZeroRate) {
  RateFilter f(2.0);
  EXPECT_FALSE(f.primed());
  EXPECT_TRUE(f.update(V::Constant(5.0), 0.033).isZero());
  EXPECT_TRUE(f.primed());
}

TEST(RateFilter, ConvergesToTheSlopeOfARamp) {
  RateFilter f(2.0);
  V slope;
  slope << 0.1, -0.2, 0.3, 0.0, 1.0, -0.5;
  const double dt = 0.033;
  for (int k = 0; k < 200; ++k) f.update(slope * (k * dt), dt);
  EXPECT_LT((f.rate() - slope).norm(), 1e-9);
}

TEST(RateFilter, LagMatchesTheCutOff) {
  // Step in slope: after one time constant the filtered rate has covered 1 - 1/e of it (the
  // discretisation makes it a little slower).
  const double dt = 0.001;
  RateFilter f(1.0);
  const int steps = static_cast<int>(std::round(f.time_constant_s() / dt));
  f.update(V::Zero(), dt);
  for (int k = 1; k <= steps; ++k) f.update(V::Constant(k * dt), dt);
  EXPECT_NEAR(f.rate()[0], 1.0 - std::exp(-1.0), 0.01);
}

TEST(RateFilter, AttenuatesMeasurementNoise) {
  // A vehicle moving at 0.2 m/s seen through 5 mm of estimate noise at 30 Hz.
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 0.005);
  const double dt = 1.0 / 30.0;
  RateFilter f(1.5);
  double prev = 0.0, raw_sq = 0.0, filt_sq = 0.0;
  int n = 0;
  for (int k = 0; k < 3000; ++k) {
    const double x = 0.2 * k * dt + noise(rng);
    const double r = f.update(V::Constant(x), dt)[0];
    if (k > 100) {
      raw_sq += std::pow((x - prev) / dt - 0.2, 2);
      filt_sq += std::pow(r - 0.2, 2);
      ++n;
    }
    prev = x;
  }
  const double raw_rms = std::sqrt(raw_sq / n), filt_rms = std::sqrt(filt_sq / n);
  EXPECT_GT(raw_rms, 0.15);             // the raw difference is useless at this noise
  EXPECT_LT(filt_rms, 0.45 * raw_rms);  // the filter removes most of it
}

TEST(RateFilter, NonPositiveDtLeavesTheStateAlone) {
  RateFilter f(2.0);
  f.update(V::Zero(), 0.033);
  f.update(V::Constant(0.033), 0.033);
  const V before = f.rate();
  EXPECT_TRUE(f.update(V::Constant(100.0), 0.0).isApprox(before));
  EXPECT_TRUE(f.update(V::Constant(100.0), -1.0).isApprox(before));
  f.reset();
  EXPECT_FALSE(f.primed());
  EXPECT_TRUE(f.rate().isZero());
}

TEST(RateFilter, RejectsBadCutOff) {
  EXPECT_THROW(RateFilter(0.0), std::invalid_argument);
  EXPECT_THROW(RateFilter(-1.0), std::invalid_argument);
}

TEST(RateFilter, RateLimitBoundsAnOutliersKick) {
  // A 0.3 m outlier at 30 Hz: unclamped it reads as 9 m/s; clamped at 0.8 m/s the kick is
  // at most the clamp, while a real 0.2 m/s motion still passes whole.
  const double dt = 1.0 / 30.0;
  RateFilter free(3.0);
  RateFilter limited(3.0, V::Constant(0.8));
  free.update(V::Zero(), dt);
  limited.update(V::Zero(), dt);
  const double kick_free = free.update(V::Constant(0.3), dt)[0];
  const double kick_limited = limited.update(V::Constant(0.3), dt)[0];
  EXPECT_GT(kick_free, 3.0);
  EXPECT_GT(kick_limited, 0.0);
  EXPECT_LE(kick_limited, 0.8);

  RateFilter ramp(3.0, V::Constant(0.8));
  for (int k = 0; k < 200; ++k) ramp.update(V::Constant(0.2 * k * dt), dt);
  EXPECT_NEAR(ramp.rate()[0], 0.2, 1e-9);
}

TEST(RateFilter, RejectsNonPositiveRateLimits) {
  EXPECT_THROW(RateFilter(3.0, V::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::control
