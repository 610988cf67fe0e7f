// The ArduSub bus of `rovctl sim`: the real MAVLink driver over loopback UDP, with the mock
// ArduSub's endpoint stepped around each call on the tick's thread, so every frame crosses a real
// socket yet what the vehicle does stays deterministic and independent of machine load.
#pragma once

#include <string>

#include "app/runtime/mock_ardusub_endpoint.hpp"
#include "drivers/mavlink/ardusub_sensors.hpp"
#include "drivers/mavlink/ardusub_thruster_bus.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::app {

class SteppedArdusubBus final : public hal::ThrusterBus {
 public:
  // `sensors` (may be null) is the one attached to `bus`; all three outlive this object.
  SteppedArdusubBus(drivers::ArdusubThrusterBus& bus, MockArdusubEndpoint& peer,
                    const drivers::ArdusubSensors* sensors);

  bool open(std::string& error) override;
  hal::BusStatus arm(bool armed) override;
  // The driver sends MANUAL_CONTROL; the peer takes it at once, so ArduSub's mixer drives the
  // simulated thrusters from this command on, as the mock bus does.
  hal::BusStatus write(const hal::ThrusterCommand& command) override;
  // The peer steps first (its streams due by now), then the driver drains them: the tick's
  // sensor read that follows sees this tick's attitude.
  hal::BusStatus read(hal::ThrusterTelemetry& telemetry) override;
  void close() override;
  std::string name() const override { return "mock ArduSub over " + bus_.name(); }

 private:
  // Steps the peer until it has taken every MANUAL_CONTROL the driver sent (loopback delivery is
  // immediate on Linux; the bounded wait is a guard, not a timing).
  void settle_peer();

  drivers::ArdusubThrusterBus& bus_;
  MockArdusubEndpoint& peer_;
  const drivers::ArdusubSensors* sensors_;
};

}  // namespace rovctl::app
