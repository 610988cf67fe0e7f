// The station charger's parameters.
#include "hal/mock/charger.hpp"

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, ChargerParams& p) {
  v.param("max_current_a", p.max_current_a,
          {"A", 0.0, 1000.0, "constant-current limit of the station's charger"});
  v.param("pin_engage_m", p.pin_engage_m,
          {"m", 0.0, 0.1, "probe tip within this of the socket bottom closes the charging pins"});
  v.param("current_sense_noise_a", p.current_sense_noise_a,
          {"A", 0.0, 10.0, "noise (std dev) of the charger's current sense"});
}

}  // namespace rovctl::hal::mock
