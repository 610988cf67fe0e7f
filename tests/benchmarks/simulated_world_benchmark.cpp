// Cost of the simulation per control tick: physics for 33 ms of sim time, and one mock stereo grab.
#include <benchmark/benchmark.h>

#include <chrono>

#include "hal/mock/mock_stereo_camera.hpp"
#include "hal/mock/simulated_world.hpp"

namespace rovctl::hal::mock {
namespace {

void BM_PhysicsPerTick(benchmark::State& state) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  ThrusterCommand c;
  c.count = 8;
  c.thrust_fraction = {0.3, 0.3, 0.3, 0.3, -0.1, -0.1, -0.1, -0.1};
  std::chrono::nanoseconds t{0};
  for (auto _ : state) {
    world.command_thrusters(c);
    t += std::chrono::milliseconds(33);
    world.step_to(t);
  }
  benchmark::DoNotOptimize(world.state().position_world_m);
}
BENCHMARK(BM_PhysicsPerTick)->Unit(benchmark::kMicrosecond);

void BM_MockStereoGrab(benchmark::State& state) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  MockStereoCamera camera(world, make_parallel_rig(CameraModel{}, 0.178), MarkerModel::standard(),
                          CameraSimParams{}, FaultInjection{}, 1);
  std::string error;
  camera.open(error);
  StereoFrame frame;
  std::chrono::nanoseconds t{0};
  for (auto _ : state) {
    t += std::chrono::milliseconds(33);
    world.step_to(t);
    benchmark::DoNotOptimize(camera.grab(frame));
  }
}
BENCHMARK(BM_MockStereoGrab)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rovctl::hal::mock
