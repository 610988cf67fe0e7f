// `rovctl run`: the vehicle. Opens the configured backends (exit 2 naming the device if one is
// missing), arms, runs the 33 ms loop until SIGINT/SIGTERM or the mission ends, and always leaves
// the thrusters neutral and disarmed.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/systemd_notify.hpp"
#include "app/runtime/vehicle.hpp"
#include "app/view/operator_view.hpp"
#include "drivers/modbus/modbus_thruster_bus.hpp"

namespace rovctl::app {
namespace {

std::atomic<Vehicle*> g_vehicle{nullptr};

extern "C" void on_stop_signal(int) {
  if (Vehicle* v = g_vehicle.load()) v->request_stop();
}

// SIGINT and SIGTERM ask the vehicle to stop for as long as this lives.
class StopSignal {
 public:
  explicit StopSignal(Vehicle& vehicle) {
    g_vehicle = &vehicle;
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
  }
  ~StopSignal() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    g_vehicle = nullptr;
  }
  StopSignal(const StopSignal&) = delete;
  StopSignal& operator=(const StopSignal&) = delete;
};

}  // namespace

int command_run(const Words& words) {
  const CliArgs args =
      CliArgs::parse("run", words, {"--config", "--max-ticks", "--telemetry"}, {"--quiet"});
  if (!args.has("--config")) throw UsageError("rovctl run: --config FILE is required");
  const AppConfig config = load_app_config(args.get("--config"));
  const hal::StereoRig rig = load_rig(config);  // both validated: nothing is opened before
  for (const std::string& w : config.warnings) std::cerr << "rovctl run: warning: " << w << "\n";
  const auto max_ticks = static_cast<std::uint64_t>(args.get_int("--max-ticks", 0, 0, 1L << 40));
  const bool quiet = args.has("--quiet");

  VehicleOptions options;
  options.telemetry_csv = args.get("--telemetry", "rovctl-telemetry.csv");
  // The operator view's link outlives the vehicle (the loop writes to it); the view, declared
  // after the vehicle, stops before it. Its port is bound before any device is opened.
  std::unique_ptr<OperatorLink> link;
  if (config.operator_view.enabled()) {
    link = std::make_unique<OperatorLink>(
        rig, std::chrono::duration_cast<std::chrono::nanoseconds>(
                 std::chrono::duration<double>(1.0 / config.operator_view.frame_rate_hz)));
    options.operator_link = link.get();
  }
  Vehicle vehicle(config, rig, make_vehicle_backends(config, rig), options);
  std::string error;
  std::unique_ptr<OperatorView> view;
  if (link) {
    view = std::make_unique<OperatorView>(config.operator_view, rig, config.marker, *link);
    if (!view->start(error)) throw ConfigError(config.config_file + ": " + error);
    if (!quiet) std::cerr << "rovctl run: operator view at " << view->url() << "\n";
    // Said even with --quiet: who can reach the vehicle's view, and whether it takes commands.
    std::cerr << "rovctl run: " << view->exposure() << "\n";
  }
  if (!vehicle.open(error)) throw ConfigError(error);
  const std::string devices =
      vehicle.backends().camera->name() + ", " + vehicle.backends().bus->name();

  if (config.control.attitude.enabled && !config.control.servo.six_dof &&
      vehicle.backends().sensors == nullptr) {
    std::cerr << "rovctl run: warning: control.attitude.enabled, but these backends give no "
                 "attitude: roll and pitch are only damped by vision\n";
  }

  // The vehicle's destructor leaves the thrusters neutral and disarmed on every way out of this
  // scope, an exception included; the signal handler only asks the loop to stop.
  const RealtimeSetupResult& rt = vehicle.enter_realtime();
  for (const auto& w : rt.warnings) std::cerr << "rovctl run: warning: " << w << "\n";
  for (const auto& a : rt.applied) {
    if (!quiet) std::cerr << "rovctl run: " << a << "\n";
  }
  StopSignal stop(vehicle);
  if (!vehicle.arm(error)) {
    std::cerr << "rovctl run: " << error << "\n";
    return kExitRuntimeFailure;
  }
  SystemdNotifier notifier;
  notifier.ready();
  if (!quiet) std::cerr << "rovctl run: armed; " << devices << "\n";
  int code = kExitOk;
  vehicle.run(max_ticks == 0 ? CyclicScheduler::kNoTickLimit : max_ticks,
              [&](const TickInfo& info) { notifier.feed_watchdog(info.wakeup); });
  notifier.stopping();
  if (vehicle.loop().failsafe().tripped()) code = kExitRuntimeFailure;
  if (!quiet) std::cerr << vehicle.scheduler().report();
  if (!vehicle.shutdown(error)) {
    // A controller that never heard "disarm" is not known to be safe: say so, and fail.
    std::cerr << "rovctl run: " << error << "\n";
    code = kExitRuntimeFailure;
  }
  if (const auto* modbus =
          dynamic_cast<const drivers::ModbusThrusterBus*>(vehicle.backends().real_bus.get());
      modbus != nullptr && !quiet) {
    std::cerr << "rovctl run: " << modbus->name() << ": "
              << drivers::summary(modbus->counters(),
                                  config.thruster_bus.modbus.response_timeout_ms)
              << "\n";
  }
  if (!quiet) {
    std::cerr << "rovctl run: stopped after " << vehicle.loop().ticks() << " ticks, mission "
              << control::to_string(vehicle.loop().mission().state()) << "\n";
  }
  return code;
}

}  // namespace rovctl::app
