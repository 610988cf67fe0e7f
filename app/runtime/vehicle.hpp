// The vehicle root: one object owns everything a flight needs — backends, scheduler, telemetry,
// the loop and its helper threads — and leaves the thrusters neutral and disarmed on every exit,
// exception included. `rovctl run`, the simulation's trial runner and the tests all build it.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/runtime/app_config.hpp"
#include "app/runtime/bus_io_thread.hpp"
#include "app/runtime/cyclic_scheduler.hpp"
#include "app/runtime/operator_link.hpp"
#include "app/runtime/telemetry.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/runtime/vehicle_loop.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

// One row of the thread table (as PX4 lists its work queues): who runs, how and how often.
struct ThreadSpec {
  std::string name;
  std::string policy;  // "SCHED_FIFO 80", "SCHED_OTHER" or "SCHED_BATCH"
  std::chrono::microseconds period{0};
  std::string role;
};

struct VehicleOptions {
  std::uint64_t seed = 1;  // the estimator's random stream
  // Flight: a telemetry writer and an event logger on their own SCHED_OTHER threads. Simulation
  // in virtual time: none; the caller drains events and telemetry between ticks.
  bool helper_threads = true;
  std::string telemetry_csv = "rovctl-telemetry.csv";  // with helper threads and telemetry on
  std::string log_prefix = "rovctl run: ";
  std::size_t min_ring_capacity = 0;
  OperatorLink* operator_link = nullptr;  // the operator view's link, or none
};

class Vehicle {
 public:
  // Builds the loop over `backends` (not yet opened). Throws ConfigError on inconsistent params.
  Vehicle(const AppConfig& config, const hal::StereoRig& rig, VehicleBackends backends,
          VehicleOptions options = {});
  ~Vehicle();  // neutral + disarm, helper threads joined, devices closed; never throws
  Vehicle(const Vehicle&) = delete;
  Vehicle& operator=(const Vehicle&) = delete;

  // Opens the camera, then the bus (closing the camera again if the bus fails); false with an
  // error naming the device.
  bool open(std::string& error);
  // Neutral, then arm; false with an error naming the bus.
  bool arm(std::string& error);
  // Runs the 33 ms loop until the mission ends, request_stop() or `max_ticks`. `after_tick` runs
  // on the loop's thread after each tick (the simulation's bookkeeping, the watchdog feed). An
  // exception out of a tick makes the vehicle safe before it leaves run().
  const SchedulerStats& run(std::uint64_t max_ticks = CyclicScheduler::kNoTickLimit,
                            const std::function<void(const TickInfo&)>& after_tick = {});
  // Applies scheduler.realtime (SCHED_FIFO, mlockall, affinity) to the calling thread, which is
  // to call run(): after every start-up allocation. Refusals come back as warnings.
  const RealtimeSetupResult& enter_realtime();
  // From a signal handler or another thread: the loop ends after the current tick.
  void request_stop() noexcept { scheduler_->request_stop(); }
  // Neutral and disarm; idempotent, never throws (a bus that fails here is reported by the loop).
  void make_safe() noexcept;
  // The end of a flight: neutral and disarm, then the bus closed. False, with a reason naming
  // the bus, when a real bus did not acknowledge the final neutral and disarm in time.
  bool shutdown(std::string& error);

  // The real bus's I/O thread (null when the bus is the mock's), for its statistics.
  const BusIoThread* bus_io() const { return bus_io_.get(); }
  // rovctl's status to the ground station (ArduSub bus only), else null.
  drivers::GcsStatus* gcs_status() { return gcs_; }

  // The thread table of this vehicle as configured.
  std::vector<ThreadSpec> threads() const;

  VehicleLoop& loop() { return *loop_; }
  const VehicleLoop& loop() const { return *loop_; }
  CyclicScheduler& scheduler() { return *scheduler_; }
  TelemetryRing& telemetry() { return ring_; }
  VehicleBackends& backends() { return backends_; }

 private:
  void start_helpers();
  void stop_helpers() noexcept;

  const AppConfig& config_;
  VehicleOptions options_;
  VehicleBackends backends_;
  // A real bus runs on its own I/O thread; the loop and open/close go through `bus_`.
  std::unique_ptr<BusIoThread> bus_io_;
  hal::ThrusterBus* bus_ = nullptr;
  std::unique_ptr<CyclicScheduler> scheduler_;
  TelemetryRing ring_;
  std::unique_ptr<VehicleLoop> loop_;
  drivers::GcsStatus* gcs_ = nullptr;  // the ArduSub bus's, when it sends status
  std::unique_ptr<TelemetryWriter> writer_;
  std::thread logger_;
  std::atomic<bool> logging_{false};
  RealtimeSetupResult realtime_;
  bool opened_ = false;
};

}  // namespace rovctl::app
