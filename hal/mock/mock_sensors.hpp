// MockSensors: depth and attitude of the simulated vehicle as its pressure sensor and AHRS would
// report them, with noise, and with injectable NaN readings and sensor loss; the dock contact, the
// battery monitor and the station charger's current sense.
#pragma once

#include <cstdint>
#include <random>

#include "hal/interfaces/sensors.hpp"
#include "hal/mock/fault_injection.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/simulated_world.hpp"

namespace rovctl::hal::mock {

class MockSensors final : public Sensors {
 public:
  MockSensors(const SimulatedWorld& world, const SensorSimParams& params,
              const FaultInjection& faults, std::uint64_t seed);

  // Depth of the body origin, attitude and body rates, with noise. No heap allocation.
  bool read(SensorReadings& readings) override;

  FaultInjection& faults() { return faults_; }

 private:
  const SimulatedWorld& world_;
  SensorSimParams params_;
  FaultInjection faults_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  // The charger's current sense has its own noise stream: the navigation noise stays as it was.
  std::mt19937_64 charger_rng_;
  std::normal_distribution<double> charger_normal_{0.0, 1.0};
};

}  // namespace rovctl::hal::mock
