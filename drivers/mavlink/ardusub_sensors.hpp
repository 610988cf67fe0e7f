// hal::Sensors from ArduSub's telemetry: the bus's I/O thread, which owns the MAVLink socket,
// hands each frame here; the tick reads the newest readings lock-free, checked for staleness.
#pragma once

#include <chrono>
#include <cstdint>

#include "drivers/mavlink/ardusub_params.hpp"
#include "drivers/mavlink/mavlink_codec.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/interfaces/sensors.hpp"
#include "hal/primitives/latest_slot.hpp"

namespace rovctl::drivers {

// The readings with when each part last arrived (on the clock).
struct ArdusubSample {
  hal::SensorReadings readings;
  std::chrono::nanoseconds attitude_stamp{0};
  std::chrono::nanoseconds depth_stamp{0};
  std::chrono::nanoseconds battery_stamp{0};
};

class ArdusubSensors final : public hal::Sensors {
 public:
  // `clock` is the tick's time base, readable from any thread.
  ArdusubSensors(const ArdusubSensorParams& params, const hal::Clock& clock);

  // I/O thread: one frame from ArduSub (already filtered by its system id). Attitude and rates
  // from ATTITUDE_QUATERNION, depth from SCALED_PRESSURE2, battery from SYS_STATUS, a leak from
  // STATUSTEXT ("Leak Detected"). Publishes when a reading changed. No allocation.
  void accept(const mavlink::Frame& frame);

  // Tick: the newest readings; each part invalid when older than stale_ms. False until ArduSub
  // has sent anything. No allocation, no lock.
  bool read(hal::SensorReadings& readings) override;

  // On the thread that calls accept(): attitude and depth have each arrived once, so the first
  // tick after arming finds them (the bus waits for this in open()).
  bool has_attitude_and_depth() const {
    return building_.readings.attitude_valid && building_.readings.depth_valid;
  }

  const ArdusubSensorParams& params() const { return params_; }
  std::uint64_t published() const { return slot_.published(); }

 private:
  ArdusubSensorParams params_;
  const hal::Clock& clock_;
  ArdusubSample building_;  // the I/O thread's
  app::LatestSlot<ArdusubSample> slot_;
};

}  // namespace rovctl::drivers
