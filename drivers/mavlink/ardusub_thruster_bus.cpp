// ArduSub thruster bus: MANUAL_CONTROL or RC_CHANNELS_OVERRIDE per command, ARM_DISARM with its
// acknowledgement, and the vehicle's HEARTBEAT watched for link loss, a disarm or a mode change we
// did not ask for.
#include "drivers/mavlink/ardusub_thruster_bus.hpp"

#include <cstdio>
#include <stdexcept>
#include <string_view>
#include <thread>

namespace rovctl::drivers {

namespace {

constexpr std::uint8_t kMavTypeGcs = 6;
constexpr std::uint8_t kMavAutopilotInvalid = 8;
constexpr std::uint8_t kMavStateActive = 4;
constexpr std::uint8_t kMavResultAccepted = 0;
// A babbling peer cannot hold the I/O thread: at most this many frames per drain.
constexpr int kMaxFramesPerPump = 256;
// Poll step while waiting for an acknowledgement or the first HEARTBEAT (start-up and the I/O
// thread only).
constexpr auto kPollStep = std::chrono::milliseconds(1);

mavlink::LinkEndpoint parse_link(const std::string& text) {
  mavlink::LinkEndpoint e;
  std::string error;
  if (!mavlink::parse_link_endpoint(text, "thruster_bus.ardusub.link", e, error)) {
    throw std::invalid_argument(error);
  }
  return e;
}

int required_mode(const std::string& name) {
  const int mode = ardusub_custom_mode(name);
  if (mode < 0) {
    throw std::invalid_argument("thruster_bus.ardusub.flight_mode: unknown ArduSub mode '" + name +
                                "'");
  }
  return mode;
}

}  // namespace

const char* to_string(ArdusubFault f) {
  switch (f) {
    case ArdusubFault::none:
      return "none";
    case ArdusubFault::link_lost:
      return "ArduSub link lost";
    case ArdusubFault::stream_silent:
      return "ArduSub silent";
    case ArdusubFault::disarmed_under_us:
      return "ArduSub disarmed";
    case ArdusubFault::mode_changed:
      return "ArduSub mode changed";
    case ArdusubFault::arm_refused:
      return "ArduSub refused arm";
  }
  return "?";
}

ArdusubThrusterBus::ArdusubThrusterBus(const ArdusubParams& params,
                                       const hal::ThrusterLayout& layout)
    : params_(params),
      thrusters_mode_(params.mode == "thrusters"),
      map_(layout, params.scale, params.pilot_gain),
      rc_map_(layout, params.rc_override),
      endpoint_(parse_link(params.link)),
      required_mode_(required_mode(params.flight_mode)),
      writer_(static_cast<std::uint8_t>(params.gcs_system_id),
              static_cast<std::uint8_t>(params.gcs_component_id)),
      thruster_count_(layout.thrusters.size()) {
  if (params.gcs_status.enabled) gcs_ = std::make_unique<GcsStatus>(params.gcs_status);
}

ArdusubThrusterBus::~ArdusubThrusterBus() { close(); }

std::string ArdusubThrusterBus::name() const {
  return "ardusub " + params_.link + " system " + std::to_string(params_.vehicle_system_id);
}

template <typename Message>
bool ArdusubThrusterBus::send(const Message& m) {
  const std::size_t n = mavlink::write_message(writer_, m, frame_);
  const bool ok = n > 0 && link_.send(std::span<const std::uint8_t>(frame_.data(), n)) ==
                               mavlink::MavlinkLink::Io::ok;
  if (!ok) ++counters_.send_failures;
  return ok;
}

bool ArdusubThrusterBus::send_heartbeat() {
  mavlink::Heartbeat hb;
  hb.type = kMavTypeGcs;
  hb.autopilot = kMavAutopilotInvalid;
  hb.system_status = kMavStateActive;
  last_heartbeat_sent_ = Clock::now();
  const bool ok = send(hb);
  if (ok) ++counters_.heartbeats_sent;
  return ok;
}

bool ArdusubThrusterBus::send_manual_control(const ArdusubAxes& axes) {
  mavlink::ManualControl mc;
  mc.x = axes.x;
  mc.y = axes.y;
  mc.z = axes.z;
  mc.r = axes.r;
  mc.target = static_cast<std::uint8_t>(params_.vehicle_system_id);
  last_axes_ = axes;
  const bool ok = send(mc);
  if (ok) ++counters_.manual_control_sent;
  return ok;
}

bool ArdusubThrusterBus::send_rc_override(const mavlink::RcChannelsOverride& m) {
  last_rc_override_ = m;
  last_rc_override_.target_system = static_cast<std::uint8_t>(params_.vehicle_system_id);
  last_rc_override_.target_component = static_cast<std::uint8_t>(params_.vehicle_component_id);
  const bool ok = send(last_rc_override_);
  if (ok) ++counters_.rc_override_sent;
  return ok;
}

bool ArdusubThrusterBus::send_command(const hal::ThrusterCommand& command) {
  if (thrusters_mode_) return send_rc_override(rc_map_.message(command, armed_));
  return send_manual_control(armed_ ? map_.axes(command) : ArdusubAxes{});
}

bool ArdusubThrusterBus::send_neutral() {
  // MANUAL_CONTROL also writes channels 1-6: in thrusters mode it would fight the override.
  if (thrusters_mode_) return send_rc_override(rc_map_.neutral());
  return send_manual_control(ArdusubAxes{});
}

void ArdusubThrusterBus::pump() {
  const auto now = Clock::now();
  for (int i = 0; i < kMaxFramesPerPump; ++i) {
    mavlink::Frame f;
    const mavlink::MavlinkLink::Io io = link_.receive(f);
    if (io != mavlink::MavlinkLink::Io::ok) break;
    if (f.header.system_id != params_.vehicle_system_id) continue;
    if (sensors_ != nullptr) sensors_->accept(f);
    if (f.header.message_id == mavlink::AttitudeQuaternion::kId) {
      last_attitude_ = now;
      ++counters_.attitude_received;
    }
    counters_.pressure_received += f.header.message_id == mavlink::ScaledPressure2::kId;
    counters_.sys_status_received += f.header.message_id == mavlink::SysStatus::kId;
    mavlink::Heartbeat hb;
    mavlink::CommandAck ack;
    mavlink::ParamValue value;
    mavlink::StatusText text;
    if (f.header.component_id == params_.vehicle_component_id && mavlink::unpack(f, hb)) {
      ++counters_.heartbeats_received;
      heartbeat_seen_ = true;
      last_heartbeat_ = now;
      vehicle_armed_ = (hb.base_mode & mavlink::kModeFlagSafetyArmed) != 0;
      vehicle_mode_ = hb.custom_mode;
      // Only after ArduSub acknowledged our arm: any HEARTBEAT it sends after the ACK shows it.
      if (armed_ && !vehicle_armed_) disarmed_under_us_ = true;
      if (armed_ && vehicle_mode_ != static_cast<std::uint32_t>(required_mode_)) {
        mode_changed_ = true;
      }
    } else if (mavlink::unpack(f, ack)) {
      ++counters_.acks_received;
      if (ack.command == mavlink::kCmdComponentArmDisarm) {
        arm_result_ = ack.result;
        ++arm_acks_;
      } else if (ack.command == mavlink::kCmdDoSetMode) {
        mode_result_ = ack.result;
        ++mode_acks_;
      }
    } else if (mavlink::unpack(f, text)) {
      // ArduSub says why it will not arm before its COMMAND_ACK ("PreArm: Gyros inconsistent",
      // "Arm: Leak Detected"); kept for the refusal's reason.
      const std::string_view t = mavlink::text_of(text.text);
      if (t.starts_with("PreArm:") || t.starts_with("Arm:")) {
        prearm_text_.fill('\0');
        t.copy(prearm_text_.data(), prearm_text_.size() - 1);
      }
    } else if (awaited_param_[0] != '\0' && mavlink::unpack(f, value) &&
               value.param_id == awaited_param_) {
      param_value_ = value.param_value;
      param_answered_ = true;
    }
  }
  if (opened_ &&
      now - last_heartbeat_sent_ >= std::chrono::milliseconds(params_.heartbeat_period_ms)) {
    (void)send_heartbeat();
  }
  if (opened_ && gcs_) {
    // Its own ids and sequence: only the socket is shared. At most a few frames per call.
    for (std::size_t n = gcs_->next_frame(now.time_since_epoch(), frame_); n > 0;
         n = gcs_->next_frame(now.time_since_epoch(), frame_)) {
      if (link_.send(std::span<const std::uint8_t>(frame_.data(), n)) !=
          mavlink::MavlinkLink::Io::ok) {
        ++counters_.send_failures;
      }
    }
  }
}

void ArdusubThrusterBus::wait_a_little() {
  if (wait_hook_) {
    wait_hook_();
  } else {
    std::this_thread::sleep_for(kPollStep);
  }
}

bool ArdusubThrusterBus::open(std::string& error) {
  if (thruster_count_ == 0) {
    error = name() + ": no thrusters to drive";
    return false;
  }
  if (!link_.is_open() && !link_.open(endpoint_, error)) return false;
  opened_ = true;
  armed_ = false;
  // udpout: ArduSub learns of us from our first datagram; udpin: it is pointed at us already.
  (void)send_heartbeat();
  const auto deadline = Clock::now() + std::chrono::milliseconds(params_.link_timeout_ms);
  while (!heartbeat_seen_ && Clock::now() < deadline) {
    pump();
    if (!heartbeat_seen_) wait_a_little();
  }
  if (!heartbeat_seen_) {
    error = name() + ": no HEARTBEAT from ArduSub (system " +
            std::to_string(params_.vehicle_system_id) + ", component " +
            std::to_string(params_.vehicle_component_id) + ") within " +
            std::to_string(params_.link_timeout_ms) + " ms";
    close();
    return false;
  }
  if (!send_neutral() || !request_streams()) {
    error = name() + ": cannot send the neutral command or the stream requests";
    close();
    return false;
  }
  // Armed before the requested streams arrive, the first ticks would find no readings and trip
  // the sensors-lost failsafe (latched): wait for them here, at start-up, as for the HEARTBEAT.
  const auto streams_deadline = Clock::now() + std::chrono::milliseconds(params_.link_timeout_ms);
  while (sensors_ != nullptr && !sensors_->has_attitude_and_depth() &&
         Clock::now() < streams_deadline) {
    wait_a_little();
    pump();
  }
  if (sensors_ != nullptr && !sensors_->has_attitude_and_depth()) {
    error = name() + ": no ATTITUDE_QUATERNION and SCALED_PRESSURE2 from ArduSub within " +
            std::to_string(params_.link_timeout_ms) + " ms of requesting them";
    close();
    return false;
  }
  return true;
}

bool ArdusubThrusterBus::request_streams() {
  if (sensors_ == nullptr) return true;
  // Not in ArduSub's default streams (ATTITUDE_QUATERNION) or not at the tick's pace: ask.
  const float interval_us = 1000.0F * static_cast<float>(sensors_->params().stream_interval_ms);
  const std::uint8_t sys = static_cast<std::uint8_t>(params_.vehicle_system_id);
  const std::uint8_t comp = static_cast<std::uint8_t>(params_.vehicle_component_id);
  return send(mavlink::set_message_interval(sys, comp, mavlink::AttitudeQuaternion::kId,
                                            interval_us)) &&
         send(mavlink::set_message_interval(sys, comp, mavlink::ScaledPressure2::kId,
                                            interval_us)) &&
         send(mavlink::set_message_interval(sys, comp, mavlink::SysStatus::kId, interval_us));
}

bool ArdusubThrusterBus::send_arm(bool arm, Clock::duration wait) {
  const std::uint64_t acks_before = arm_acks_;
  if (!send(mavlink::arm_disarm(static_cast<std::uint8_t>(params_.vehicle_system_id),
                                static_cast<std::uint8_t>(params_.vehicle_component_id), arm,
                                false))) {
    return false;
  }
  const auto deadline = Clock::now() + wait;
  while (arm_acks_ == acks_before && Clock::now() < deadline) {
    wait_a_little();
    pump();
  }
  return arm_acks_ != acks_before && arm_result_ == kMavResultAccepted;
}

hal::BusStatus ArdusubThrusterBus::arm(bool armed) {
  if (!opened_) return hal::BusStatus::fault;
  pump();
  const auto wait = std::chrono::milliseconds(params_.ack_timeout_ms);
  if (!armed) {
    armed_ = false;
    const bool neutral = send_neutral();
    return neutral && send_arm(false, wait) ? hal::BusStatus::ok : hal::BusStatus::fault;
  }
  // Arming clears what the last arming's watch found; a refusal is a fault until the next try.
  disarmed_under_us_ = false;
  mode_changed_ = false;
  arm_refused_ = false;
  if (status() == hal::BusStatus::fault) return hal::BusStatus::fault;
  if (!set_flight_mode()) {
    arm_refused_ = true;
    char what[96];
    std::snprintf(what, sizeof(what), "ArduSub stayed in mode %u after DO_SET_MODE %s (%d)%s",
                  static_cast<unsigned>(vehicle_mode_), params_.flight_mode.c_str(), required_mode_,
                  mode_answered_ ? ", refused" : ", no answer");
    explain_refusal(what);
    return hal::BusStatus::fault;
  }
  prearm_text_.fill('\0');
  const std::uint64_t acks_before = arm_acks_;
  if (!send_neutral() || !send_arm(true, wait)) {
    arm_refused_ = true;
    // Its PreArm STATUSTEXT may trail the ACK by a frame or two.
    for (int i = 0; i < 20 && prearm_text_[0] == '\0'; ++i) {
      wait_a_little();
      pump();
    }
    char what[96];
    if (arm_acks_ == acks_before) {
      std::snprintf(what, sizeof(what), "ArduSub refused arm: no COMMAND_ACK within %d ms",
                    params_.ack_timeout_ms);
    } else {
      std::snprintf(what, sizeof(what), "ArduSub refused arm (MAV_RESULT %u)",
                    static_cast<unsigned>(arm_result_));
    }
    explain_refusal(what);
    return hal::BusStatus::fault;
  }
  armed_ = true;
  return status();
}

bool ArdusubThrusterBus::set_flight_mode() {
  const auto required = static_cast<std::uint32_t>(required_mode_);
  if (vehicle_mode_ == required) return true;
  if (!send(mavlink::do_set_mode(static_cast<std::uint8_t>(params_.vehicle_system_id),
                                 static_cast<std::uint8_t>(params_.vehicle_component_id),
                                 required))) {
    return false;
  }
  // ArduSub beats at 1 Hz: its ACK is the answer in time to arm, and the watch on its HEARTBEAT
  // (mode_changed) confirms the mode from the next beat on.
  const std::uint64_t acks_before = mode_acks_;
  const auto deadline = Clock::now() + std::chrono::milliseconds(params_.ack_timeout_ms);
  while (vehicle_mode_ != required && mode_acks_ == acks_before && Clock::now() < deadline) {
    wait_a_little();
    pump();
  }
  mode_answered_ = mode_acks_ != acks_before;
  return vehicle_mode_ == required || (mode_answered_ && mode_result_ == kMavResultAccepted);
}

void ArdusubThrusterBus::explain_refusal(const char* what) {
  std::array<char, 160>& out = reasons_[next_reason_];
  next_reason_ ^= 1U;
  if (prearm_text_[0] != '\0') {
    std::snprintf(out.data(), out.size(), "%s: %s", what, prearm_text_.data());
  } else {
    std::snprintf(out.data(), out.size(), "%s", what);
  }
  explained_ = ArdusubFault::arm_refused;
  fault_reason_.store(out.data(), std::memory_order_release);
}

void ArdusubThrusterBus::explain(ArdusubFault f, Clock::time_point now) {
  if (f == explained_) return;
  explained_ = f;
  // None keeps the last reason (the tick may still be logging it); a refusal was said with
  // ArduSub's own words by explain_refusal().
  if (f == ArdusubFault::none || f == ArdusubFault::arm_refused) return;
  std::array<char, 160>& out = reasons_[next_reason_];
  next_reason_ ^= 1U;
  const auto ms = [now](Clock::time_point since) {
    return static_cast<long long>(
        std::chrono::duration_cast<std::chrono::milliseconds>(now - since).count());
  };
  switch (f) {
    case ArdusubFault::link_lost:
      if (heartbeat_seen_) {
        std::snprintf(out.data(), out.size(), "%s: no HEARTBEAT for %lld ms (limit %d ms)",
                      to_string(f), ms(last_heartbeat_), params_.link_timeout_ms);
      } else {
        std::snprintf(out.data(), out.size(), "%s: no HEARTBEAT yet", to_string(f));
      }
      break;
    case ArdusubFault::stream_silent:
      std::snprintf(out.data(), out.size(),
                    "%s: no ATTITUDE_QUATERNION for %lld ms (limit %d ms; HEARTBEAT %lld ms ago)",
                    to_string(f), ms(last_attitude_), params_.stream_timeout_ms,
                    ms(last_heartbeat_));
      break;
    case ArdusubFault::mode_changed:
      std::snprintf(out.data(), out.size(), "%s: mode %u, not %s (%d)", to_string(f),
                    static_cast<unsigned>(vehicle_mode_), params_.flight_mode.c_str(),
                    required_mode_);
      break;
    default:
      std::snprintf(out.data(), out.size(), "%s", to_string(f));
      break;
  }
  fault_reason_.store(out.data(), std::memory_order_release);
}

std::optional<float> ArdusubThrusterBus::read_parameter(std::string_view id) {
  if (!opened_) return std::nullopt;
  mavlink::ParamRequestRead request;
  request.param_index = -1;  // by name
  request.target_system = static_cast<std::uint8_t>(params_.vehicle_system_id);
  request.target_component = static_cast<std::uint8_t>(params_.vehicle_component_id);
  mavlink::set_text(request.param_id, id);
  awaited_param_ = request.param_id;
  param_answered_ = false;
  for (int attempt = 0; attempt < 3 && !param_answered_; ++attempt) {
    if (!send(request)) break;
    const auto sent = Clock::now();
    const auto deadline = sent + std::chrono::milliseconds(params_.ack_timeout_ms);
    while (!param_answered_ && Clock::now() < deadline) {
      wait_a_little();
      pump();
    }
    if (param_answered_) {
      round_trip_ = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - sent);
    }
  }
  awaited_param_ = {};
  if (!param_answered_) return std::nullopt;
  return param_value_;
}

std::optional<std::string> ArdusubThrusterBus::run_prearm_checks() {
  if (!opened_) return std::nullopt;
  prearm_text_.fill('\0');
  const std::uint64_t acks_before = counters_.acks_received;
  if (!send(mavlink::run_prearm_checks(static_cast<std::uint8_t>(params_.vehicle_system_id),
                                       static_cast<std::uint8_t>(params_.vehicle_component_id)))) {
    return std::nullopt;
  }
  const auto wait = std::chrono::milliseconds(params_.ack_timeout_ms);
  auto deadline = Clock::now() + wait;
  bool acknowledged = false;
  while (Clock::now() < deadline && prearm_text_[0] == '\0') {
    wait_a_little();
    pump();
    if (!acknowledged && counters_.acks_received != acks_before) {
      acknowledged = true;
      deadline = Clock::now() + wait;  // the failures follow the ACK
    }
  }
  if (!acknowledged && prearm_text_[0] == '\0') return std::nullopt;
  return std::string(prearm_text_.data());
}

ArdusubThrusterBus::ArrivalRates ArdusubThrusterBus::measure_arrivals(
    std::chrono::milliseconds window) {
  const ArdusubCounters before = counters_;
  const auto start = Clock::now();
  while (Clock::now() - start < window) {
    wait_a_little();
    pump();
  }
  const double s = std::chrono::duration<double>(Clock::now() - start).count();
  ArrivalRates r;
  r.heartbeat_hz =
      static_cast<double>(counters_.heartbeats_received - before.heartbeats_received) / s;
  r.attitude_hz = static_cast<double>(counters_.attitude_received - before.attitude_received) / s;
  r.pressure_hz = static_cast<double>(counters_.pressure_received - before.pressure_received) / s;
  r.sys_status_hz =
      static_cast<double>(counters_.sys_status_received - before.sys_status_received) / s;
  return r;
}

ArdusubFault ArdusubThrusterBus::fault() const {
  const auto now = Clock::now();
  if (!heartbeat_seen_ ||
      now - last_heartbeat_ > std::chrono::milliseconds(params_.link_timeout_ms)) {
    return ArdusubFault::link_lost;
  }
  // The attitude stream (asked at the tick's pace) tells a silent ArduSub long before its 1 Hz
  // HEARTBEAT can; open() waited for its first message.
  if (sensors_ != nullptr && opened_ &&
      now - last_attitude_ > std::chrono::milliseconds(params_.stream_timeout_ms)) {
    return ArdusubFault::stream_silent;
  }
  if (disarmed_under_us_) return ArdusubFault::disarmed_under_us;
  if (mode_changed_) return ArdusubFault::mode_changed;
  if (arm_refused_) return ArdusubFault::arm_refused;
  return ArdusubFault::none;
}

hal::BusStatus ArdusubThrusterBus::status() {
  if (!opened_) return hal::BusStatus::fault;
  const ArdusubFault f = fault();
  explain(f, Clock::now());
  if (f != ArdusubFault::none) return hal::BusStatus::fault;
  return send_failed_ ? hal::BusStatus::degraded : hal::BusStatus::ok;
}

hal::BusStatus ArdusubThrusterBus::write(const hal::ThrusterCommand& command) {
  if (!opened_) return hal::BusStatus::fault;
  pump();
  send_failed_ = !send_command(command);
  return status();
}

hal::BusStatus ArdusubThrusterBus::read(hal::ThrusterTelemetry& telemetry) {
  telemetry = hal::ThrusterTelemetry{};
  telemetry.count = thruster_count_;
  telemetry.valid = false;
  if (!opened_) return hal::BusStatus::fault;
  pump();
  return status();
}

void ArdusubThrusterBus::close() {
  if (opened_ && link_.is_open()) {
    // Best effort on every way out: neutral first, then the disarm with a bounded wait.
    armed_ = false;
    (void)send_neutral();
    (void)send_arm(false, std::chrono::milliseconds(params_.ack_timeout_ms));
  }
  opened_ = false;
  armed_ = false;
  link_.close();
}

}  // namespace rovctl::drivers
