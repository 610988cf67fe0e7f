// The charging faults and how each is injected.
#include "app/tools/charge_fault.hpp"

#include <cstring>

namespace rovctl::app {
namespace {

// Seated this long before a fault: the hold has settled, the charge is well under way.
constexpr double kAfterSeatedS = 3.0;

constexpr ChargeFault kChargeFaults[] = {
    {"none", "nothing", "departed", "charge complete"},
    {"knock", "one knock out of the socket", "departed", "probe unseated: re-seat"},
    {"knocks", "a knock each time the probe seats, one more than max_reseats", "abort",
     "undocked after the re-seats ran out"},
    {"surge", "a 0.26 m/s cross-current rising over 5 s", "departed",
     "current beyond what the hold resists"},
    {"charger", "the charger delivers no current", "departed", "charger reports no current"},
    {"operator", "the operator asks to undock", "departed", "operator command"},
    {"camera", "the stereo camera is lost (failsafe)", "undock",
     "failsafe: backing out of the socket"},
    {nullptr, nullptr, nullptr, nullptr},
};

}  // namespace

const ChargeFault* charge_faults() { return kChargeFaults; }

std::string charge_fault_names_text() {
  std::string text;
  for (const ChargeFault* f = kChargeFaults; f->name != nullptr; ++f) {
    if (!text.empty()) text += ", ";
    text += f->name;
  }
  return text;
}

const ChargeFault* find_charge_fault(const std::string& name) {
  for (const ChargeFault* f = kChargeFaults; f->name != nullptr; ++f) {
    if (name == f->name) return f;
  }
  return nullptr;
}

void apply_charge_fault(const ChargeFault& f, AppConfig& config, TrialOptions& options) {
  hal::mock::FaultInjection& faults = config.sim.faults;
  const std::string name = f.name;
  if (name == "knock" || name == "knocks") {
    faults.knock_after_seated_s = kAfterSeatedS;
    faults.knock_count = name == "knock" ? 1 : config.mission.recharge.max_reseats + 1;
  } else if (name == "surge") {
    faults.surge_after_seated_s = kAfterSeatedS;
  } else if (name == "charger") {
    faults.charger_fails_at_s = 0.0;
  } else if (name == "operator") {
    options.undock_request_after_charging_s = kAfterSeatedS;
  } else if (name == "camera") {
    faults.camera_lost_after_seated_s = kAfterSeatedS;
  }
}

}  // namespace rovctl::app
