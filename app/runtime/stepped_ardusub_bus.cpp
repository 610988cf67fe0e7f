// Peer and driver stepped in a fixed order per call: the determinism of `rovctl sim` over MAVLink.
#include "app/runtime/stepped_ardusub_bus.hpp"

#include <chrono>
#include <thread>

namespace rovctl::app {

namespace {
// Bound on the wait for a datagram already sent on loopback (never reached in practice).
constexpr auto kDeliveryGuard = std::chrono::milliseconds(200);
}  // namespace

SteppedArdusubBus::SteppedArdusubBus(drivers::ArdusubThrusterBus& bus, MockArdusubEndpoint& peer,
                                     const drivers::ArdusubSensors* sensors)
    : bus_(bus), peer_(peer), sensors_(sensors) {}

void SteppedArdusubBus::settle_peer() {
  const auto give_up = std::chrono::steady_clock::now() + kDeliveryGuard;
  peer_.service();
  // Until the peer has taken every command sent: MANUAL_CONTROL (wrench mode) or
  // RC_CHANNELS_OVERRIDE (thrusters mode).
  while (peer_.counters().manual_control + peer_.counters().rc_override <
             bus_.counters().manual_control_sent + bus_.counters().rc_override_sent &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::yield();
    peer_.service();
  }
}

bool SteppedArdusubBus::open(std::string& error) {
  const bool ok = bus_.open(error);
  if (ok) settle_peer();
  return ok;
}

hal::BusStatus SteppedArdusubBus::arm(bool armed) {
  const hal::BusStatus s = bus_.arm(armed);
  settle_peer();
  return s;
}

hal::BusStatus SteppedArdusubBus::write(const hal::ThrusterCommand& command) {
  const hal::BusStatus s = bus_.write(command);
  settle_peer();
  return s;
}

hal::BusStatus SteppedArdusubBus::read(hal::ThrusterTelemetry& telemetry) {
  peer_.service();
  hal::BusStatus s = bus_.read(telemetry);
  if (sensors_ == nullptr) return s;
  // Until the driver has drained every sensor frame the peer streamed (each one publishes).
  const auto give_up = std::chrono::steady_clock::now() + kDeliveryGuard;
  while (sensors_->published() < peer_.sensor_frames_sent() &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::yield();
    s = bus_.read(telemetry);
  }
  return s;
}

void SteppedArdusubBus::close() {
  bus_.close();
  peer_.service();
}

}  // namespace rovctl::app
