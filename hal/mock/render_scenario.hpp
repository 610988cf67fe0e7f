// The named imaging conditions the simulated cameras can render (`sim.scenario`), and every
// scenario's parameters in one place.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hal/mock/bubble_field.hpp"
#include "hal/mock/camera_response.hpp"
#include "hal/mock/passing_bar.hpp"
#include "hal/mock/side_light.hpp"
#include "hal/mock/water_optics.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

enum class Scenario { clear, turbid, side_light, bubbles, occluders, noisy, exposure };

// "clear", "turbid", ... in the enum's order: the config's choices and the CLI's list.
const std::vector<std::string>& scenario_names();
// All names as one "clear, turbid, ..." string, for error messages.
std::string scenario_names_text();
const char* to_string(Scenario s);
// False when `name` is none of scenario_names().
bool scenario_from_name(std::string_view name, Scenario& out);

// Each scenario's own parameters, used only when that scenario is selected.
struct ScenarioParams {
  TurbidWater turbid;
  SideLight side_light;
  BubbleParams bubbles;
  PassingBar occluders;
  NoisyCamera noisy;
  ExposureDrift exposure;
};

void describe(ParamVisitor& v, ScenarioParams& p);

// What a renderer needs to draw one scenario: which, its parameters, and the seed that lays out
// its random parts (bubbles, particles), shared by both views so they see the same scene.
struct SceneConditions {
  Scenario scenario = Scenario::clear;
  ScenarioParams params;
  std::uint64_t seed = 0;
};

// The conditions for the scenario named `name`; throws std::invalid_argument naming
// sim.scenario and the valid names when it is unknown.
SceneConditions scene_conditions(const std::string& name, const ScenarioParams& params,
                                 std::uint64_t seed);

}  // namespace rovctl::hal::mock
