// Coulomb counting in energy (Wh) against a linear open-circuit voltage: coarse, but the
// recharging mission needs the charge's duration and the hold's share of it, not the chemistry.
#include "hal/mock/battery_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, BatteryParams& p) {
  v.param("capacity_wh", p.capacity_wh, {"Wh", 1.0, 1e5, "usable energy from empty to full"});
  v.param("empty_voltage_v", p.empty_voltage_v,
          {"V", 1.0, 1000.0, "open-circuit voltage at SoC 0 (linear in SoC)"});
  v.param("full_voltage_v", p.full_voltage_v,
          {"V", 1.0, 1000.0, "open-circuit voltage at SoC 1, the charger's CV set-point"});
  v.param("taper_start_soc_fraction", p.taper_start_soc_fraction,
          {"-", 0.0, 1.0, "SoC above which the accepted current tapers linearly to 0 at full"});
  v.param("max_charge_current_a", p.max_charge_current_a,
          {"A", 0.0, 1000.0, "largest charge current the battery accepts"});
  v.param("thruster_power_w_per_n1_5", p.thruster_power_w_per_n1_5,
          {"W/N^1.5", 0.0, 100.0, "thruster electrical power P = k |F|^1.5 per thruster"});
  v.param("hotel_power_w", p.hotel_power_w,
          {"W", 0.0, 10000.0, "electronics' constant draw (not counted as the hold's energy)"});
}

double thruster_power_w(const ThrusterModel& thrusters, double w_per_n1_5) {
  double p = 0.0;
  for (std::size_t i = 0; i < thrusters.count(); ++i) {
    p += w_per_n1_5 * std::pow(std::abs(thrusters.thrust_n(i)), 1.5);
  }
  return p;
}

BatteryModel::BatteryModel(const BatteryParams& params) : p_(params) {}

void BatteryModel::reset(double soc_fraction) {
  soc_ = std::clamp(soc_fraction, 0.0, 1.0);
  charged_wh_ = 0.0;
  thruster_wh_ = 0.0;
}

double BatteryModel::voltage_v() const {
  return p_.empty_voltage_v + soc_ * (p_.full_voltage_v - p_.empty_voltage_v);
}

double BatteryModel::accepted_current_a(double offer_a) const {
  double limit = p_.max_charge_current_a;
  if (soc_ > p_.taper_start_soc_fraction) {
    const double span = std::max(1e-6, 1.0 - p_.taper_start_soc_fraction);
    limit *= std::max(0.0, (1.0 - soc_) / span);
  }
  return std::clamp(offer_a, 0.0, limit);
}

void BatteryModel::step(double dt_s, double charger_offer_a, double thruster_power_w) {
  if (dt_s <= 0.0) return;
  const double hours = dt_s / 3600.0;
  const double v = voltage_v();
  // In the taper the charger holds the bus at its set-point and still feeds the loads: a hold
  // that drew from the battery there would stall the charge below full however long it lasted.
  const double load_a = (thruster_power_w + p_.hotel_power_w) / v;
  charger_current_a_ =
      std::clamp(accepted_current_a(std::numeric_limits<double>::infinity()) + load_a, 0.0,
                 std::max(0.0, charger_offer_a));
  const double battery_a = charger_current_a_ - load_a;
  charge_current_a_ = std::max(0.0, battery_a);
  charged_wh_ += charger_current_a_ * v * hours;
  thruster_wh_ += thruster_power_w * hours;
  soc_ = std::clamp(soc_ + battery_a * v * hours / p_.capacity_wh, 0.0, 1.0);
}

}  // namespace rovctl::hal::mock
