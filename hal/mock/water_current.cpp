// Water current: a Gauss-Markov driver g_{k+1} = a g_k + s sqrt(1 - a^2) n_k (a = exp(-dt / tau))
// low-passed with the same tau; s = sqrt(2) sigma gives the smoothed part the stationary std sigma.
#include "hal/mock/water_current.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace rovctl::hal::mock {

WaterCurrent::WaterCurrent(const WaterCurrentParams& params, std::uint64_t seed) : p_(params) {
  reset(seed);
}

void WaterCurrent::reset(std::uint64_t seed) {
  rng_.seed(seed);
  normal_.reset();
  // Start near the stationary distribution so a trial does not begin in an unnaturally calm sea.
  for (int k = 0; k < 3; ++k) {
    driver_(k) = std::sqrt(2.0) * p_.random_sigma_mps(k) * normal_(rng_);
    random_(k) = p_.random_sigma_mps(k) * normal_(rng_);
  }
  rate_ = (driver_ - random_) / p_.correlation_time_s;
  gust_rng_.seed(seed ^ 0x5bd1e995u);
  time_s_ = 0.0;
  gust_start_s_ = -1.0;
  gust_next_s_ = std::exponential_distribution<double>(1.0 / p_.gust_interval_s)(gust_rng_);
  mean_now_ = p_.mean_world_mps;
  gust_.setZero();
}

void WaterCurrent::step_tide_and_gusts(double dt_s) {
  time_s_ += dt_s;
  const Eigen::Vector3d before = mean_now_ + gust_;
  if (p_.tide_turn_degps != 0.0) {
    mean_now_ =
        Eigen::AngleAxisd(p_.tide_turn_degps * M_PI / 180.0 * time_s_, Eigen::Vector3d::UnitZ()) *
        p_.mean_world_mps;
  }
  if (p_.gust_peak_mps > 0.0) {
    if (gust_start_s_ < 0.0 && time_s_ >= gust_next_s_) {
      gust_start_s_ = time_s_;
      gust_amplitude_mps_ =
          p_.gust_peak_mps * std::uniform_real_distribution<double>(0.5, 1.0)(gust_rng_);
    }
    gust_.setZero();
    if (gust_start_s_ >= 0.0) {
      const double phase = (time_s_ - gust_start_s_) / p_.gust_duration_s;
      if (phase >= 1.0) {
        gust_start_s_ = -1.0;
        gust_next_s_ =
            time_s_ + std::exponential_distribution<double>(1.0 / p_.gust_interval_s)(gust_rng_);
      } else {
        Eigen::Vector3d dir(mean_now_.x(), mean_now_.y(), 0.0);
        if (dir.norm() < 1e-6) dir = Eigen::Vector3d::UnitX();
        gust_ = dir.normalized() * gust_amplitude_mps_ * 0.5 * (1.0 - std::cos(2.0 * M_PI * phase));
      }
    }
  }
  rate_ += (mean_now_ + gust_ - before) / dt_s;
}

void WaterCurrent::step(double dt_s) {
  if (dt_s <= 0.0) return;
  const double a = std::exp(-dt_s / p_.correlation_time_s);
  const double b = std::sqrt(1.0 - a * a);
  for (int k = 0; k < 3; ++k) {
    driver_(k) = a * driver_(k) + b * std::sqrt(2.0) * p_.random_sigma_mps(k) * normal_(rng_);
  }
  random_ += (1.0 - a) * (driver_ - random_);
  rate_ = (driver_ - random_) / p_.correlation_time_s;
  if (p_.tide_turn_degps != 0.0 || p_.gust_peak_mps > 0.0) step_tide_and_gusts(dt_s);
}

void describe(ParamVisitor& v, WaterCurrentParams& p) {
  v.param("mean_world_mps", p.mean_world_mps,
          {"m/s", -2.0, 2.0, "constant current in the world frame (NED); trials replace it"});
  v.param("random_sigma_mps", p.random_sigma_mps,
          {"m/s", 0.0, 0.5, "standard deviation of the slowly varying part, per NED axis"});
  v.param("correlation_time_s", p.correlation_time_s,
          {"s", 0.1, 1000.0, "correlation time of the varying part (Gauss-Markov)"});
  v.param("tide_turn_degps", p.tide_turn_degps,
          {"deg/s", -10.0, 10.0, "rate at which the tide turns the constant part (0 = steady)"});
  v.param("gust_peak_mps", p.gust_peak_mps,
          {"m/s", 0.0, 1.0, "largest gust along the current's direction (0 = no gusts)"});
  v.param("gust_duration_s", p.gust_duration_s,
          {"s", 0.1, 600.0, "length of one gust (raised-cosine pulse)"});
  v.param("gust_interval_s", p.gust_interval_s,
          {"s", 0.1, 3600.0, "mean gap between gusts (exponentially distributed)"});
}

}  // namespace rovctl::hal::mock
