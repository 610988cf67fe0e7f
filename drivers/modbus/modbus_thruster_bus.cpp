// Modbus thruster bus: one FC06 heartbeat and one FC16 write of the eight command registers per
// tick, FC04 for telemetry; late answers are taken, thrust is never re-sent, N failed ticks make a
// fault.
#include "drivers/modbus/modbus_thruster_bus.hpp"

#include <modbus.h>

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace rovctl::drivers {
namespace {

char parity_char(const std::string& parity) {
  if (parity == "even") return 'E';
  if (parity == "odd") return 'O';
  return 'N';
}

bool link_broken(int err) {
  return err == ECONNRESET || err == EPIPE || err == ENOTCONN || err == EBADF ||
         err == ECONNREFUSED;
}

}  // namespace

std::int16_t thrust_permille(double thrust_fraction) {
  if (!std::isfinite(thrust_fraction)) return 0;
  const double clamped = std::clamp(thrust_fraction, -1.0, 1.0);
  return static_cast<std::int16_t>(std::lround(clamped * 1000.0));
}

std::string summary(const ModbusCounters& c, int response_timeout_ms) {
  std::uint64_t total = 0;
  for (auto n : c.latency_ms) total += n;
  auto below = [&](double share) {  // upper edge of the bin holding that share
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < c.latency_ms.size(); ++i) {
      seen += c.latency_ms[i];
      if (seen > 0 && static_cast<double>(seen) >= share * static_cast<double>(total)) {
        return std::to_string(i + 1) + (i + 1 == c.latency_ms.size() ? "+" : "");
      }
    }
    return std::string("-");
  };
  return std::to_string(c.transactions) + " requests answered in p50 " + below(0.5) + " / p99 " +
         below(0.99) + " / max " + below(1.0) + " ms (" + std::to_string(c.late) + " after the " +
         std::to_string(response_timeout_ms) + " ms response timeout, taken late), " +
         std::to_string(c.errors) + " failed attempts, " + std::to_string(c.failed_ticks) +
         " failed ticks";
}

ModbusThrusterBus::ModbusThrusterBus(const ModbusParams& params, std::size_t thruster_count)
    : params_(params),
      thruster_count_(std::min<std::size_t>(thruster_count, modbus_map::kChannels)) {
  if (params_.transport == "tcp") {
    name_ = "modbus tcp " + params_.host + ":" + std::to_string(params_.port) + " slave " +
            std::to_string(params_.slave_id);
  } else {
    name_ = "modbus rtu " + params_.serial_device + " (" + std::to_string(params_.baud) +
            " bit/s) slave " + std::to_string(params_.slave_id);
  }
}

ModbusThrusterBus::~ModbusThrusterBus() { close(); }

std::string ModbusThrusterBus::name() const { return name_; }

bool ModbusThrusterBus::open(std::string& error) {
  close();
  if (thruster_count_ == 0) {
    error = name_ + ": no thrusters to drive";
    return false;
  }
  ctx_ = params_.transport == "tcp"
             ? modbus_new_tcp(params_.host.c_str(), params_.port)
             : modbus_new_rtu(params_.serial_device.c_str(), params_.baud,
                              parity_char(params_.parity), params_.data_bits, params_.stop_bits);
  if (ctx_ == nullptr) {
    error = name_ + ": cannot create the Modbus context: " + modbus_strerror(errno);
    return false;
  }
  auto fail = [&](const std::string& what) {
    error = name_ + ": " + what;
    counters_.last_error = error;
    close();
    return false;
  };
  if (modbus_set_slave(ctx_, params_.slave_id) != 0) {
    return fail(std::string("invalid slave id: ") + modbus_strerror(errno));
  }
  // Wait for a late answer too: a slow controller executes the request anyway, and an answer left
  // unread arrives during the next request, which then fails on it (with a 15 ms controller on a
  // loaded machine one miss of the 20 ms timeout failed every request after it).
  late_after_ = std::chrono::milliseconds(params_.response_timeout_ms);
  const int timeout_ms = params_.response_timeout_ms + params_.late_answer_ms;
  modbus_set_response_timeout(ctx_, static_cast<std::uint32_t>(timeout_ms / 1000),
                              static_cast<std::uint32_t>((timeout_ms % 1000) * 1000));
  if (modbus_connect(ctx_) != 0) {
    return fail(std::string(params_.transport == "tcp" ? "cannot connect: "
                                                       : "cannot open the serial port: ") +
                modbus_strerror(errno));
  }
  connected_ = true;
  if (params_.transport == "rtu" && params_.rs485 &&
      modbus_rtu_set_serial_mode(ctx_, MODBUS_RTU_RS485) != 0) {
    return fail(std::string("cannot switch the port to RS-485 mode: ") + modbus_strerror(errno));
  }
  // Start from a known safe state: neutral commands, disarmed. This is also the proof that the
  // controller answers at all.
  armed_ = false;
  command_registers_.fill(0);
  if (!transact(Op::write_commands) || !transact(Op::write_armed, 0)) {
    return fail("the thruster controller does not answer (" + counters_.last_error + ")");
  }
  counters_.consecutive_failures = 0;
  return true;
}

bool ModbusThrusterBus::attempt(Op op, std::uint16_t value) {
  if (!connected_) {
    if (modbus_connect(ctx_) != 0) return false;
    connected_ = true;
  }
  int rc = -1;
  const auto sent = std::chrono::steady_clock::now();
  switch (op) {
    case Op::write_commands:
      rc = modbus_write_registers(ctx_, modbus_map::kCommandRegister, modbus_map::kChannels,
                                  command_registers_.data());
      break;
    case Op::write_heartbeat:
      rc = modbus_write_register(ctx_, modbus_map::kHeartbeatRegister, value);
      break;
    case Op::write_armed:
      rc = modbus_write_register(ctx_, modbus_map::kArmedRegister, value);
      break;
    case Op::read_inputs:
      rc = modbus_read_input_registers(ctx_, modbus_map::kSpeedRegister,
                                       static_cast<int>(input_registers_.size()),
                                       input_registers_.data());
      break;
  }
  if (rc >= 0) {
    const auto took = std::chrono::steady_clock::now() - sent;
    if (took > late_after_) ++counters_.late;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(took).count();
    ++counters_.latency_ms[static_cast<std::size_t>(
        std::clamp<std::int64_t>(ms, 0, static_cast<std::int64_t>(kLatencyBins) - 1))];
    return true;
  }
  const int err = errno;
  if (params_.transport == "tcp" && (link_broken(err) || err == ETIMEDOUT || err == EMBBADDATA)) {
    // An answer past the window, or one to an abandoned request (its transaction id is not this
    // one's), would arrive during the next request and fail it in turn: a new connection leaves
    // every straggler behind on the old one.
    modbus_close(ctx_);
    connected_ = false;
  } else {
    modbus_flush(ctx_);  // drop a late answer so it is not taken for the next one
  }
  errno = err;
  return false;
}

bool ModbusThrusterBus::transact(Op op, std::uint16_t value, int retries) {
  if (ctx_ == nullptr) return false;
  if (retries < 0) retries = params_.retries;
  for (int i = 0; i <= retries; ++i) {
    if (attempt(op, value)) {
      ++counters_.transactions;
      return true;
    }
    ++counters_.errors;
  }
  // modbus_strerror returns static strings; building last_error allocates, but only on failure.
  counters_.last_error = modbus_strerror(errno);
  return false;
}

hal::BusStatus ModbusThrusterBus::finish_tick(bool ok) {
  if (ok) {
    counters_.consecutive_failures = 0;
    return hal::BusStatus::ok;
  }
  ++counters_.failed_ticks;
  ++counters_.consecutive_failures;
  return counters_.consecutive_failures >= params_.max_consecutive_failures
             ? hal::BusStatus::fault
             : hal::BusStatus::degraded;
}

bool ModbusThrusterBus::write_neutral() {
  command_registers_.fill(0);
  return transact(Op::write_commands);
}

hal::BusStatus ModbusThrusterBus::arm(bool armed) {
  if (ctx_ == nullptr) return hal::BusStatus::fault;
  bool ok = true;
  if (!armed) {
    armed_ = false;
    ok = write_neutral();
    ok = transact(Op::write_armed, 0) && ok;
  } else {
    // Arm from neutral, so the thrusters never jump to a stale command.
    ok = write_neutral() && transact(Op::write_armed, 1);
    armed_ = ok;
  }
  return finish_tick(ok);
}

hal::BusStatus ModbusThrusterBus::write(const hal::ThrusterCommand& command) {
  if (ctx_ == nullptr) return hal::BusStatus::fault;
  for (std::size_t i = 0; i < command_registers_.size(); ++i) {
    const bool drive = armed_ && i < thruster_count_ && i < command.count;
    command_registers_[i] =
        static_cast<std::uint16_t>(drive ? thrust_permille(command.thrust_fraction[i]) : 0);
  }
  ++heartbeat_;
  // The heartbeat first, harmless if a hung controller executes it when it resumes: thrust goes
  // only to a controller that has just answered, and once, since a copy sent to a silent one
  // would run late. The commands fail: the next tick's are fresher, and a controller that hears
  // no more heartbeats stops on its own.
  const std::uint64_t errors_before = counters_.errors;
  bool ok = transact(Op::write_heartbeat, heartbeat_);
  // A heartbeat that needed a retry found the controller silent for a whole answer window: the
  // command has aged by as much, and the controller may be hanging. Thrust waits for the next tick.
  ok = ok && counters_.errors == errors_before && transact(Op::write_commands, 0, /*retries=*/0);
  return finish_tick(ok);
}

hal::BusStatus ModbusThrusterBus::read(hal::ThrusterTelemetry& telemetry) {
  if (ctx_ == nullptr) {
    telemetry = telemetry_;
    telemetry.valid = false;
    return hal::BusStatus::fault;
  }
  const bool ok = transact(Op::read_inputs);
  if (ok) {
    telemetry_.count = thruster_count_;
    for (std::size_t i = 0; i < thruster_count_; ++i) {
      telemetry_.speed_rpm[i] = static_cast<std::int16_t>(input_registers_[i]);
      telemetry_.fault_flags[i] = input_registers_[modbus_map::kChannels + i];
    }
  }
  telemetry_.valid = ok;
  telemetry = telemetry_;
  return finish_tick(ok);
}

void ModbusThrusterBus::close() {
  if (ctx_ == nullptr) return;
  if (connected_) {
    // Best effort, one attempt each: neutral, then disarmed. Even if these are lost the
    // controller stops on the stalled heartbeat.
    command_registers_.fill(0);
    (void)attempt(Op::write_commands, 0);
    (void)attempt(Op::write_armed, 0);
    modbus_close(ctx_);
  }
  modbus_free(ctx_);
  ctx_ = nullptr;
  connected_ = false;
  armed_ = false;
}

}  // namespace rovctl::drivers
