// `rovctl thrusters --test`: ArduSub-style motor test — each thruster in turn at a low command
// for a moment, heartbeat kept, neutral between and after; asks first unless --yes.
// `rovctl thrusters --safe`: neutral and disarmed, then exit (the unit's ExecStopPost).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "drivers/thruster_bus_factory.hpp"

namespace rovctl::app {
namespace {

// After `rovctl run` died without closing the bus (SIGKILL, a crash, the systemd watchdog), the
// controller still holds its last command and armed = 1 until its own heartbeat watchdog acts:
// open the bus alone (no camera, no calibration), write neutral, disarm, and say whether the
// controller acknowledged. Never arms. Tries again until `timeout`, since the dead process's
// last request may still hold the controller for a moment.
int make_safe(const AppConfig& config, std::chrono::milliseconds timeout) {
  std::unique_ptr<hal::ThrusterBus> bus =
      drivers::make_thruster_bus(config.thruster_bus, config.vehicle.thrusters);
  if (bus == nullptr) {
    std::cout << "rovctl thrusters: thruster_bus.backend mock: no controller to make safe\n";
    return kExitOk;
  }
  const auto until = std::chrono::steady_clock::now() + timeout;
  std::string error;
  while (true) {
    // open() commands neutral and disarmed and fails unless the controller answered both.
    if (bus->open(error) && bus->arm(false) == hal::BusStatus::ok) {
      bus->close();
      std::cout << "rovctl thrusters: " << bus->name() << ": neutral and disarmed\n";
      return kExitOk;
    }
    bus->close();
    if (std::chrono::steady_clock::now() >= until) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::cerr << "rovctl thrusters: " << bus->name()
            << ": neutral and disarm not acknowledged within " << timeout.count() << " ms ("
            << error << "); the controller's heartbeat watchdog is what stops the thrusters now\n";
  return kExitRuntimeFailure;
}

}  // namespace

int command_thrusters(const Words& words) {
  const CliArgs args =
      CliArgs::parse("thrusters", words, {"--config", "--level", "--seconds", "--timeout-ms"},
                     {"--test", "--yes", "--safe"});
  if (!args.has("--config")) throw UsageError("rovctl thrusters: --config FILE is required");
  if (args.has("--test") == args.has("--safe")) {
    throw UsageError(
        "rovctl thrusters: say --test to run the motor test, or --safe to command neutral and "
        "disarm");
  }
  if (args.has("--safe")) {
    const auto timeout_ms = args.get_int("--timeout-ms", 1000, 10, 60000);
    return make_safe(load_app_config(args.get("--config")), std::chrono::milliseconds(timeout_ms));
  }
  const double level = args.get_double("--level", 0.15, 0.01, 0.5);
  const double seconds = args.get_double("--seconds", 1.0, 0.1, 10.0);
  const AppConfig config = load_app_config(args.get("--config"));
  const hal::StereoRig rig = load_rig(config);
  VehicleBackends hw = make_vehicle_backends(config, rig);
  std::string error;
  if (!hw.bus->open(error)) throw ConfigError(error);

  const auto& thrusters = config.vehicle.thrusters.thrusters;
  if (!args.has("--yes")) {
    std::cout << "The motor test spins each of the " << thrusters.size() << " thrusters on "
              << hw.bus->name() << " at " << level * 100.0 << " % for " << seconds
              << " s.\nKeep hands and cables clear. Type 'yes' to continue: " << std::flush;
    std::string answer;
    if (!std::getline(std::cin, answer) || answer != "yes") {
      std::cout << "motor test cancelled\n";
      hw.bus->close();
      return kExitRuntimeFailure;
    }
  }
  hal::ThrusterCommand command;
  command.count = thrusters.size();
  auto hold = [&](std::chrono::nanoseconds duration) {
    const std::chrono::nanoseconds period(33'000'000);
    const auto end = hw.clock->now() + duration;
    hal::BusStatus status = hal::BusStatus::ok;
    for (auto next = hw.clock->now(); next < end; next += period) {
      status = hw.bus->write(command);
      if (status == hal::BusStatus::fault) return status;
      hw.clock->sleep_until(next + period);
    }
    return status;
  };
  int code = kExitOk;
  if (hw.bus->arm(true) == hal::BusStatus::fault) {
    std::cerr << "rovctl thrusters: " << hw.bus->name() << ": could not arm\n";
    code = kExitRuntimeFailure;
  }
  for (std::size_t i = 0; i < thrusters.size() && code == kExitOk; ++i) {
    command.thrust_fraction.fill(0.0);
    const auto channel = static_cast<std::size_t>(thrusters[i].channel);
    command.thrust_fraction[channel] = level;
    std::cout << "thruster " << i + 1 << " (" << thrusters[i].name << ", channel " << channel
              << ") at " << level * 100.0 << " %" << std::flush;
    if (hold(std::chrono::duration_cast<std::chrono::nanoseconds>(
            std::chrono::duration<double>(seconds))) == hal::BusStatus::fault) {
      std::cout << ": bus fault\n";
      code = kExitRuntimeFailure;
      break;
    }
    hal::ThrusterTelemetry telemetry;
    if (hw.bus->read(telemetry) != hal::BusStatus::fault && telemetry.valid &&
        channel < telemetry.count) {
      std::printf(": %.0f rpm, faults 0x%04x\n", telemetry.speed_rpm[channel],
                  telemetry.fault_flags[channel]);
    } else {
      std::cout << ": no speed telemetry\n";
    }
    command.thrust_fraction.fill(0.0);
    hold(std::chrono::milliseconds(500));
  }
  hw.bus->arm(false);
  hw.bus->close();
  std::cout << (code == kExitOk ? "motor test complete\n" : "motor test stopped\n");
  return code;
}

}  // namespace rovctl::app
