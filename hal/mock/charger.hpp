// The charger on the docking station: it offers current through the socket's pins while the probe
// is seated, and senses what flows. Its fault (no output while seated) is injectable.
#pragma once

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

struct ChargerParams {
  double max_current_a = 18.0;  // the charger's constant-current limit
  // The pins touch when the probe tip is within this of the socket bottom (and in the socket).
  double pin_engage_m = 0.004;
  double current_sense_noise_a = 0.05;  // std dev of the reported current
};

void describe(ParamVisitor& v, ChargerParams& p);

class Charger {
 public:
  explicit Charger(const ChargerParams& params) : p_(params) {}

  // The current offered now: the limit when the pins touch, nothing when not or when failed.
  double offer_a(bool seated, bool failed) const {
    return seated && !failed ? p_.max_current_a : 0.0;
  }
  const ChargerParams& params() const { return p_; }

 private:
  ChargerParams p_;
};

}  // namespace rovctl::hal::mock
