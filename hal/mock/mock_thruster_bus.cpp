// The simulated ESC bus: delivery into the thruster model (at once, or through a slow peer in
// virtual time), arming and injected bus faults.
#include "hal/mock/mock_thruster_bus.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rovctl::hal::mock {

namespace {
// T200 at 16 V: about 3800 rpm at full thrust; thrust grows with the square of the speed.
constexpr double kFullThrustRpm = 3800.0;
// What a dead thruster's ESC reports (any non-zero flag is a fault to the controller).
constexpr std::uint16_t kInjectedFaultFlag = 0x0001;

bool all_zero(const ThrusterCommand& c) {
  for (std::size_t i = 0; i < c.count && i < kMaxThrusters; ++i) {
    if (c.thrust_fraction[i] != 0.0) return false;
  }
  return true;
}

// How long the peer takes to answer a request sent at `sent_at`.
std::chrono::nanoseconds peer_latency(const FaultInjection& faults,
                                      std::chrono::nanoseconds sent_at) {
  const bool slow = FaultInjection::active(faults.bus_slow_at_s, faults.bus_slow_for_s, sent_at);
  return std::chrono::nanoseconds(slow ? std::llround(faults.bus_latency_ms * 1e6) : 0);
}
}  // namespace

MockThrusterBus::MockThrusterBus(SimulatedWorld& world, const FaultInjection& faults)
    : world_(world), faults_(faults) {}

bool MockThrusterBus::timed_out() const {
  return FaultInjection::active(faults_.bus_timeout_at_s, world_.time());
}

bool MockThrusterBus::open(std::string& error) {
  if (faults_.bus_open_fails) {
    error = "mock thruster bus: open failed (injected fault sim.faults.bus_open_fails)";
    return false;
  }
  open_ = true;
  armed_ = false;
  world_.neutral_thrusters();
  return true;
}

BusStatus MockThrusterBus::arm(bool armed) {
  if (!open_ || timed_out()) return BusStatus::fault;
  if (!armed && FaultInjection::active(faults_.disarm_ignored_at_s, world_.time())) {
    return BusStatus::fault;  // not acknowledged: the ESCs stay armed
  }
  if (!armed) {
    world_.neutral_thrusters();
    in_flight_ = slot_full_ = false;  // disarmed ESCs drop what they were asked
  }
  armed_ = armed;
  return BusStatus::ok;
}

BusStatus MockThrusterBus::write(const ThrusterCommand& command) {
  last_command_ = command;
  ++write_count_;
  if (!open_ || timed_out()) return BusStatus::fault;  // nothing arrives; the ESCs time out
  if (!armed_) {
    world_.neutral_thrusters();
    return BusStatus::ok;
  }
  ThrusterCommand delivered = command;
  bool finite = true;
  for (std::size_t i = 0; i < delivered.count && i < kMaxThrusters; ++i) {
    if (!std::isfinite(delivered.thrust_fraction[i])) {
      delivered.thrust_fraction[i] = 0.0;
      finite = false;
    }
  }
  if (!finite) ++non_finite_count_;
  const std::chrono::nanoseconds now = world_.time();
  if (all_zero(delivered)) last_neutral_at_ = now;
  serve(now);
  if (in_flight_) {
    slot_command_ = delivered;  // replaces an unsent one: never sent late
    slot_written_at_ = now;
    slot_full_ = true;
  } else {
    in_flight_ = true;
    in_flight_command_ = delivered;
    in_flight_written_at_ = in_flight_sent_at_ = now;
    in_flight_due_ = now + peer_latency(faults_, now);
  }
  serve(now);
  if (!finite) return BusStatus::degraded;
  return peer_status(now);
}

void MockThrusterBus::serve(std::chrono::nanoseconds now) {
  while (in_flight_ && in_flight_due_ <= now) {
    deliver(in_flight_command_, in_flight_written_at_);
    const std::chrono::nanoseconds answered_at = in_flight_due_;
    in_flight_ = slot_full_;
    if (!slot_full_) break;
    // The peer answered: the newest command goes out now, at the latency of that moment.
    slot_full_ = false;
    in_flight_command_ = slot_command_;
    in_flight_written_at_ = slot_written_at_;
    in_flight_sent_at_ = answered_at;
    if (!all_zero(slot_command_) && last_neutral_at_ > slot_written_at_) ++stale_sent_;
    in_flight_due_ = answered_at + peer_latency(faults_, answered_at);
  }
}

void MockThrusterBus::deliver(const ThrusterCommand& command, std::chrono::nanoseconds written_at) {
  if (!all_zero(command) && last_neutral_at_ > written_at) ++landed_after_neutral_;
  world_.command_thrusters(command);
}

BusStatus MockThrusterBus::peer_status(std::chrono::nanoseconds now) const {
  return in_flight_ && in_flight_sent_at_ < now ? BusStatus::degraded : BusStatus::ok;
}

BusStatus MockThrusterBus::read(ThrusterTelemetry& telemetry) {
  telemetry.valid = false;
  if (!open_ || timed_out()) return BusStatus::fault;
  const std::chrono::nanoseconds now = world_.time();
  serve(now);
  const ThrusterModel& model = world_.thrusters();
  const double now_s = std::chrono::duration<double>(world_.time()).count();
  // By bus channel, as the real buses report.
  telemetry.speed_rpm.fill(0.0);
  telemetry.fault_flags.fill(0);
  telemetry.count = 0;
  for (std::size_t i = 0; i < model.count(); ++i) {
    const double full =
        model.thrust_n(i) >= 0.0 ? model.static_thrust_n(i, 1.0) : -model.static_thrust_n(i, -1.0);
    const double ratio = full > 0.0 ? std::abs(model.thrust_n(i)) / full : 0.0;
    const auto ch = static_cast<std::size_t>(model.channel(i));
    telemetry.speed_rpm[ch] = std::copysign(kFullThrustRpm * std::sqrt(ratio), model.thrust_n(i));
    telemetry.fault_flags[ch] = model.fault_flagged(i, now_s) ? kInjectedFaultFlag : 0;
    telemetry.count = std::max(telemetry.count, ch + 1);
  }
  telemetry.valid = true;
  return peer_status(now);
}

void MockThrusterBus::close() {
  if (open_ && !timed_out()) world_.neutral_thrusters();
  armed_ = false;
  open_ = false;
}

}  // namespace rovctl::hal::mock
