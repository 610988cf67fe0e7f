// Whether ArduSub will obey rovctl at all: it takes MANUAL_CONTROL and RC_CHANNELS_OVERRIDE only
// from its ground station's system id, which must be the id rovctl sends as.
#pragma once

#include <array>
#include <optional>

#include "drivers/mavlink/ardusub_failsafe_params.hpp"

namespace rovctl::drivers {

// The parameter's name before ArduSub 4.7 and from it on; `rovctl check` reads them in this order.
inline constexpr std::array<const char*, 2> kArdusubGcsIdParams = {"SYSID_MYGCS", "MAV_GCS_SYSID"};

// `values` in kArdusubGcsIdParams's order (none: not answered). Judged on the first answered;
// unsafe when it differs from `gcs_system_id` (every command would be ignored, silently) or when
// ArduSub answered neither.
ArdusubFailsafeVerdict judge_ardusub_gcs_id(int gcs_system_id,
                                            const std::array<std::optional<float>, 2>& values);

}  // namespace rovctl::drivers
