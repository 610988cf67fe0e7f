// Water current: a Gauss-Markov driver g_{k+1} = a g_k + s sqrt(1 - a^2) n_k (a = exp(-dt / tau))
// low-passed with the same tau; s = sqrt(2) sigma gives the smoothed part the stationary std sigma.
#include "hal/mock/water_current.hpp"

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
}

void describe(ParamVisitor& v, WaterCurrentParams& p) {
  v.param("mean_world_mps", p.mean_world_mps,
          {"m/s", -2.0, 2.0, "constant current in the world frame (NED); trials replace it"});
  v.param("random_sigma_mps", p.random_sigma_mps,
          {"m/s", 0.0, 0.5, "standard deviation of the slowly varying part, per NED axis"});
  v.param("correlation_time_s", p.correlation_time_s,
          {"s", 0.1, 1000.0, "correlation time of the varying part (Gauss-Markov)"});
}

}  // namespace rovctl::hal::mock
