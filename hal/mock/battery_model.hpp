// The vehicle's battery as the recharging mission sees it: state of charge, the current it accepts
// from a charger (constant current, then a constant-voltage taper), and what the thrusters draw.
// The charger sits on the vehicle's bus beside the battery: it feeds the thrusters and the
// electronics first, and the battery takes what it accepts of the rest.
#pragma once

#include "hal/mock/thruster_model.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// Defaults: Blue Robotics' 4S Li-ion, 14.8 V 18 Ah (266 Wh), and T200 thrusters at 16 V, whose
// published curve (about 10 W at 0.5 kgf, 30 W at 1 kgf, 80 W at 2 kgf) fits P = k F^1.5.
struct BatteryParams {
  double capacity_wh = 266.0;
  double empty_voltage_v = 13.2;  // open-circuit voltage at SoC 0 (linear in SoC up to full)
  double full_voltage_v = 16.8;
  // Above this SoC the accepted current tapers linearly to zero at SoC 1 (the CV phase).
  double taper_start_soc_fraction = 0.8;
  double max_charge_current_a = 18.0;       // 1 C
  double thruster_power_w_per_n1_5 = 0.95;  // P = k |F|^1.5 per thruster
  double hotel_power_w = 20.0;              // computer, cameras, lights: not the hold's energy
};

void describe(ParamVisitor& v, BatteryParams& p);

// Electrical power of the thrusters producing their present thrust.
double thruster_power_w(const ThrusterModel& thrusters, double w_per_n1_5);

class BatteryModel {
 public:
  explicit BatteryModel(const BatteryParams& params);

  void reset(double soc_fraction);

  // The current the battery takes at its present SoC when a charger offers up to `offer_a`.
  double accepted_current_a(double offer_a) const;

  // `dt_s` with a charger offering up to `charger_offer_a` on the bus while the thrusters draw
  // `thruster_power_w` and the electronics the hotel load: the charger gives the loads plus what
  // the battery accepts, within its offer; a load beyond the offer comes out of the battery.
  void step(double dt_s, double charger_offer_a, double thruster_power_w);

  double soc_fraction() const { return soc_; }
  double voltage_v() const;
  double charged_wh() const { return charged_wh_; }  // energy the charger gave (loads included)
  // The last step's current into the battery (0 while it discharges) and out of the charger.
  double charge_current_a() const { return charge_current_a_; }
  double charger_current_a() const { return charger_current_a_; }
  double thruster_wh() const { return thruster_wh_; }
  const BatteryParams& params() const { return p_; }

 private:
  BatteryParams p_;
  double soc_ = 0.5;
  double charged_wh_ = 0.0;
  double thruster_wh_ = 0.0;
  double charge_current_a_ = 0.0;
  double charger_current_a_ = 0.0;
};

}  // namespace rovctl::hal::mock
