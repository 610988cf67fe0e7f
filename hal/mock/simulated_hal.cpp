// Wiring of one trial's mock HAL.
#include "hal/mock/simulated_hal.hpp"

namespace rovctl::hal::mock {

namespace {
SimulatedWorld& placed(SimulatedWorld& world, const TrialConditions& trial) {
  world.reset(trial.initial, trial.current_mean_world_mps, trial.world_seed);
  return world;
}
}  // namespace

SimulatedHal::SimulatedHal(const SimParams& params, const VehicleGeometry& vehicle,
                           const DockingStation& station, const StereoRig& rig,
                           const MarkerModel& marker, const TrialConditions& trial)
    : trial_(trial),
      params_(params_for_trial(params, trial)),
      world_(params_, vehicle, station),
      clock_(placed(world_, trial_),
             params_.realtime ? SimClock::Mode::realtime : SimClock::Mode::virtual_time),
      camera_(world_, rig, marker, params_.camera, params_.faults, trial_.camera_seed),
      bus_(world_, params_.faults),
      sensors_(world_, params_.sensors, params_.faults, trial_.sensor_seed) {
  camera_.stall_clock(&clock_);
}

}  // namespace rovctl::hal::mock
