// ArduSub's GCS id against rovctl's thruster_bus.ardusub.gcs_system_id.
#include "drivers/mavlink/ardusub_gcs_id.hpp"

#include <cmath>
#include <string>

namespace rovctl::drivers {

ArdusubFailsafeVerdict judge_ardusub_gcs_id(int gcs_system_id,
                                            const std::array<std::optional<float>, 2>& values) {
  ArdusubFailsafeVerdict v;
  const std::string ours = std::to_string(gcs_system_id);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!values[i]) continue;
    v.name = kArdusubGcsIdParams[i];
    v.value = values[i];
    const long theirs = std::lround(*values[i]);
    v.safe = theirs == gcs_system_id;
    v.reason = v.safe
                   ? ours + ": ArduSub obeys the system id rovctl sends as"
                   : std::to_string(theirs) + ": ArduSub obeys system id " +
                         std::to_string(theirs) + " only, and rovctl sends as " + ours +
                         " (thruster_bus.ardusub.gcs_system_id): every command would be "
                         "ignored; set " +
                         v.name + " to " + ours + " or gcs_system_id to " + std::to_string(theirs);
    return v;
  }
  v.name = std::string(kArdusubGcsIdParams[0]) + "/" + kArdusubGcsIdParams[1];
  v.reason = "ArduSub answered neither: whether it obeys system id " + ours + " is unknown";
  return v;
}

}  // namespace rovctl::drivers
