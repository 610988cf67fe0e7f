// The vehicle root's wiring and its guarantees: start-up order, the helper threads, and the safe
// state on every way out of run() and of the object itself.
#include "app/runtime/vehicle.hpp"

#include <algorithm>
#include <iostream>

#include "app/runtime/errors.hpp"
#include "app/runtime/gcs_event_text.hpp"
#include "app/runtime/realtime_setup.hpp"
#include "drivers/mavlink/ardusub_thruster_bus.hpp"

namespace rovctl::app {
namespace {

constexpr std::chrono::milliseconds kLoggerPeriod{50};

// Only a real bus on a real clock gets the I/O thread. The mock bus answers at once in-process
// (nothing to hide) and drives the simulated world that the tick's mock camera renders without a
// lock: on another thread it would race. And in virtual time (a stepped `rovctl sim`, or a test's
// wrapper around the mock) the order of command and physics step would depend on the OS
// scheduler, and commands would look stale after a virtual-time jump: stepped synchronously the
// simulation stays deterministic.
bool needs_io_thread(const VehicleBackends& b) {
  if (!b.real_bus || b.bus != b.real_bus.get()) return false;
  return !b.sim || b.sim->clock().mode() == hal::mock::SimClock::Mode::realtime;
}

std::chrono::microseconds us(double ms) {
  return std::chrono::microseconds(static_cast<std::int64_t>(ms * 1000.0));
}

}  // namespace

Vehicle::Vehicle(const AppConfig& config, const hal::StereoRig& rig, VehicleBackends backends,
                 VehicleOptions options)
    : config_(config),
      options_(std::move(options)),
      backends_(std::move(backends)),
      bus_io_(needs_io_thread(backends_)
                  ? std::make_unique<BusIoThread>(*backends_.bus, *backends_.clock,
                                                  config.thruster_bus.timing)
                  : nullptr),
      bus_(bus_io_ ? static_cast<hal::ThrusterBus*>(bus_io_.get()) : backends_.bus),
      scheduler_(std::make_unique<CyclicScheduler>(*backends_.clock, config.scheduler)),
      ring_(std::max(static_cast<std::size_t>(config.telemetry.ring_capacity),
                     options_.min_ring_capacity)) {
  const bool telemetry_on = config.telemetry.enabled || !options_.helper_threads;
  loop_ =
      std::make_unique<VehicleLoop>(config, rig, *backends_.camera, *bus_, backends_.sensors,
                                    *scheduler_, telemetry_on ? &ring_ : nullptr, options_.seed);
  loop_->attach_operator(options_.operator_link);
  // ArduSub's link also carries rovctl's status to the ground station: the tick posts its
  // values, the event logger its texts, the thread running the bus frames and sends them.
  if (auto* ardusub = dynamic_cast<drivers::ArdusubThrusterBus*>(backends_.real_bus.get())) {
    gcs_ = ardusub->gcs_status();
    loop_->attach_gcs(gcs_);
  }
}

Vehicle::~Vehicle() {
  make_safe();
  stop_helpers();
  if (opened_) {
    try {
      bus_->close();
      backends_.camera->close();
    } catch (...) {
      // A destructor must not throw; the bus's own close already commanded neutral.
    }
  }
}

bool Vehicle::open(std::string& error) {
  if (!backends_.camera->open(error)) return false;
  if (!bus_->open(error)) {
    backends_.camera->close();
    return false;
  }
  opened_ = true;
  return true;
}

bool Vehicle::arm(std::string& error) {
  start_helpers();
  return loop_->arm(error);
}

const SchedulerStats& Vehicle::run(std::uint64_t max_ticks,
                                   const std::function<void(const TickInfo&)>& after_tick) {
  try {
    return scheduler_->run(
        [&](const TickInfo& info) {
          const bool more = loop_->tick(info);
          if (after_tick) after_tick(info);
          return more;
        },
        max_ticks);
  } catch (...) {
    make_safe();
    throw;
  }
}

bool Vehicle::shutdown(std::string& error) {
  make_safe();
  if (!opened_) return true;
  bus_->close();  // the I/O thread's final neutral + disarm, waited for at most close_timeout_ms
  if (bus_io_ && !bus_io_->safe_acknowledged()) {
    error = bus_->name() + ": the final neutral and disarm were not acknowledged within " +
            std::to_string(config_.thruster_bus.timing.close_timeout_ms) +
            " ms (thruster_bus.timing.close_timeout_ms); the controller's watchdog is what stops "
            "the thrusters now";
    return false;
  }
  return true;
}

const RealtimeSetupResult& Vehicle::enter_realtime() {
  realtime_ = apply_realtime_setup(config_.scheduler.realtime);
  return realtime_;
}

void Vehicle::make_safe() noexcept {
  try {
    loop_->disarm();
  } catch (...) {
    // The loop could not reach the bus: its close() (destructor) sends neutral again.
  }
}

void Vehicle::start_helpers() {
  if (!options_.helper_threads || logging_.load()) return;
  if (config_.telemetry.enabled) {
    writer_ = std::make_unique<TelemetryWriter>(
        ring_, options_.telemetry_csv,
        std::chrono::milliseconds(static_cast<int>(config_.telemetry.drain_period_ms)));
    writer_->start();
  }
  logging_ = true;
  logger_ = std::thread([this]() {
    make_thread_non_realtime();
    LoopEvent e;
    const auto log = [this](const LoopEvent& event) {
      std::cerr << options_.log_prefix << format_event(event) << "\n";
      if (gcs_ != nullptr) {
        const GcsEventText t = gcs_event_text(event);
        (void)gcs_->post_text(t.severity, t.text());
      }
    };
    while (logging_.load()) {
      while (loop_->pop_event(e)) log(e);
      std::this_thread::sleep_for(kLoggerPeriod);
    }
    while (loop_->pop_event(e)) log(e);
  });
}

void Vehicle::stop_helpers() noexcept {
  logging_ = false;
  if (logger_.joinable()) logger_.join();
  if (writer_) {
    try {
      writer_->stop();
    } catch (const std::exception& e) {
      std::cerr << options_.log_prefix << e.what() << "\n";
    }
  }
}

std::vector<ThreadSpec> Vehicle::threads() const {
  const RealtimeParams& rt = config_.scheduler.realtime;
  std::vector<ThreadSpec> table;
  table.push_back({"tick",
                   rt.sched_fifo ? "SCHED_FIFO " + std::to_string(rt.priority) : "SCHED_OTHER",
                   us(config_.scheduler.period_ms),
                   "capture, estimate, control, actuate, telemetry record; allocates nothing"});
  if (bus_io_) {
    table.push_back({"bus I/O", "SCHED_BATCH", us(config_.scheduler.period_ms),
                     "newest command to the thruster bus, telemetry back; the tick never waits "
                     "for the peer"});
  }
  if (options_.helper_threads) {
    if (config_.telemetry.enabled) {
      table.push_back({"telemetry writer", "SCHED_OTHER", us(config_.telemetry.drain_period_ms),
                       "drains the telemetry ring into CSV"});
    }
    table.push_back(
        {"event logger", "SCHED_OTHER", kLoggerPeriod, "mission and failsafe events to the log"});
  }
  return table;
}

}  // namespace rovctl::app
