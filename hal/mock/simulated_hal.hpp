// SimulatedHal: one docking trial's whole mock HAL in one object — the world placed at the
// trial's start, its clock, stereo camera, thruster bus and sensors — so `rovctl sim`, the
// tests and hardware-in-the-loop runs build it the same way.
#pragma once

#include "hal/mock/mock_sensors.hpp"
#include "hal/mock/mock_stereo_camera.hpp"
#include "hal/mock/mock_thruster_bus.hpp"
#include "hal/mock/sim_clock.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/simulated_world.hpp"
#include "hal/mock/trial_generator.hpp"
#include "hal/model/docking_station.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::hal::mock {

class SimulatedHal {
 public:
  // The clock runs in real time when params.realtime is set, else in virtual time.
  SimulatedHal(const SimParams& params, const VehicleGeometry& vehicle,
               const DockingStation& station, const StereoRig& rig, const MarkerModel& marker,
               const TrialConditions& trial);
  SimulatedHal(const SimulatedHal&) = delete;
  SimulatedHal& operator=(const SimulatedHal&) = delete;

  SimulatedWorld& world() { return world_; }
  SimClock& clock() { return clock_; }
  MockStereoCamera& camera() { return camera_; }
  MockThrusterBus& bus() { return bus_; }
  MockSensors& sensors() { return sensors_; }
  const TrialConditions& trial() const { return trial_; }

 private:
  TrialConditions trial_;
  SimParams params_;
  SimulatedWorld world_;
  SimClock clock_;
  MockStereoCamera camera_;
  MockThrusterBus bus_;
  MockSensors sensors_;
};

}  // namespace rovctl::hal::mock
