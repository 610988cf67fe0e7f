// `rovctl run`: the vehicle. Opens the configured backends (exit 2 naming the device if one is
// missing), arms, runs the 33 ms loop until SIGINT/SIGTERM or the mission ends, and always leaves
// the thrusters neutral and disarmed.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <thread>

#include "app/app_config.hpp"
#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "app/cyclic_scheduler.hpp"
#include "app/errors.hpp"
#include "app/realtime_setup.hpp"
#include "app/systemd_notify.hpp"
#include "app/telemetry.hpp"
#include "app/vehicle_backends.hpp"
#include "app/vehicle_loop.hpp"

namespace rovctl::app {
namespace {

std::atomic<CyclicScheduler*> g_scheduler{nullptr};

extern "C" void on_stop_signal(int) {
  if (CyclicScheduler* s = g_scheduler.load()) s->request_stop();
}

}  // namespace

int command_run(const Words& words) {
  const CliArgs args =
      CliArgs::parse("run", words, {"--config", "--max-ticks", "--telemetry"}, {"--quiet"});
  if (!args.has("--config")) throw UsageError("rovctl run: --config FILE is required");
  const AppConfig config = load_app_config(args.get("--config"));
  const hal::StereoRig rig = load_rig(config);
  const auto max_ticks = static_cast<std::uint64_t>(args.get_int("--max-ticks", 0, 0, 1L << 40));
  const bool quiet = args.has("--quiet");

  VehicleBackends hw = make_vehicle_backends(config, rig);
  std::string error;
  if (!hw.camera->open(error)) throw ConfigError(error);
  if (!hw.bus->open(error)) {
    hw.camera->close();
    throw ConfigError(error);
  }

  auto scheduler = std::make_unique<CyclicScheduler>(*hw.clock, config.scheduler);
  TelemetryRing ring(static_cast<std::size_t>(config.telemetry.ring_capacity));
  std::unique_ptr<TelemetryWriter> writer;
  if (config.telemetry.enabled) {
    writer = std::make_unique<TelemetryWriter>(
        ring, args.get("--telemetry", "rovctl-telemetry.csv"),
        std::chrono::milliseconds(static_cast<int>(config.telemetry.drain_period_ms)));
    writer->start();
  }
  VehicleLoop loop(config, rig, *hw.camera, *hw.bus, hw.sensors, *scheduler,
                   config.telemetry.enabled ? &ring : nullptr, 1);

  if (config.control.attitude.enabled && !config.control.servo.six_dof && hw.sensors == nullptr) {
    std::cerr << "rovctl run: warning: control.attitude.enabled, but these backends give no "
                 "attitude: roll and pitch are only damped by vision\n";
  }

  // Real-time set-up after the allocations above; refusals are warnings.
  const RealtimeSetupResult rt = apply_realtime_setup(config.scheduler.realtime);
  for (const auto& w : rt.warnings) std::cerr << "rovctl run: warning: " << w << "\n";
  for (const auto& a : rt.applied) {
    if (!quiet) std::cerr << "rovctl run: " << a << "\n";
  }

  g_scheduler = scheduler.get();
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);

  // Events are logged by a non-real-time thread; the tick only queues them.
  std::atomic<bool> logging{true};
  std::thread logger([&]() {
    make_thread_non_realtime();
    LoopEvent e;
    while (logging.load()) {
      while (loop.pop_event(e)) std::cerr << "rovctl run: " << format_event(e) << "\n";
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    while (loop.pop_event(e)) std::cerr << "rovctl run: " << format_event(e) << "\n";
  });

  int code = kExitOk;
  if (!loop.arm(error)) {
    std::cerr << "rovctl run: " << error << "\n";
    code = kExitRuntimeFailure;
  } else {
    SystemdNotifier notifier;
    notifier.ready();
    if (!quiet)
      std::cerr << "rovctl run: armed; " << hw.camera->name() << ", " << hw.bus->name() << "\n";
    const SchedulerStats& stats = scheduler->run(
        [&](const TickInfo& info) {
          notifier.feed_watchdog(info.wakeup);
          return loop.tick(info);
        },
        max_ticks == 0 ? CyclicScheduler::kNoTickLimit : max_ticks);
    notifier.stopping();
    if (loop.failsafe().tripped()) code = kExitRuntimeFailure;
    if (!quiet) std::cerr << scheduler->report();
    (void)stats;
  }
  loop.disarm();
  hw.bus->close();
  hw.camera->close();
  g_scheduler = nullptr;
  logging = false;
  logger.join();
  if (writer) writer->stop();
  if (!quiet) {
    std::cerr << "rovctl run: stopped after " << loop.ticks() << " ticks, mission "
              << control::to_string(loop.mission().state()) << "\n";
  }
  return code;
}

}  // namespace rovctl::app
