// Scenario names and the declarations of every scenario's parameters (`sim.scenarios.*`).
#include "hal/mock/render_scenario.hpp"

#include <array>
#include <stdexcept>

namespace rovctl::hal::mock {
namespace {

constexpr std::array<const char*, 7> kNames = {"clear",     "turbid", "side_light", "bubbles",
                                               "occluders", "noisy",  "exposure"};

}  // namespace

const std::vector<std::string>& scenario_names() {
  static const std::vector<std::string> names(kNames.begin(), kNames.end());
  return names;
}

std::string scenario_names_text() {
  std::string all;
  for (const char* n : kNames) all += (all.empty() ? "" : ", ") + std::string(n);
  return all;
}

const char* to_string(Scenario s) { return kNames[static_cast<std::size_t>(s)]; }

bool scenario_from_name(std::string_view name, Scenario& out) {
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (name == kNames[i]) {
      out = static_cast<Scenario>(i);
      return true;
    }
  }
  return false;
}

void describe(ParamVisitor& v, ScenarioParams& p) {
  v.section("turbid", "coastal water: per-channel attenuation with range plus backscatter veil",
            [&p](ParamVisitor& s) { describe(s, p.turbid); });
  v.section("side_light", "a strong directional light from one side, with cast shadows",
            [&p](ParamVisitor& s) { describe(s, p.side_light); });
  v.section("bubbles", "rising air bubbles and floating particles in front of the station",
            [&p](ParamVisitor& s) { describe(s, p.bubbles); });
  v.section("occluders", "a dark bar (cable, fin) sweeping across in front of the marker",
            [&p](ParamVisitor& s) { describe(s, p.occluders); });
  v.section("noisy", "high sensor gain and lossy block compression",
            [&p](ParamVisitor& s) { describe(s, p.noisy); });
  v.section("exposure",
            "dim water and a vibrating camera mount: an auto exposure drifting between under- "
            "and over-exposure and smearing the marker, or camera.v4l2's manual exposure",
            [&p](ParamVisitor& s) { describe(s, p.exposure); });
}

SceneConditions scene_conditions(const std::string& name, const ScenarioParams& params,
                                 std::uint64_t seed) {
  SceneConditions c;
  if (!scenario_from_name(name, c.scenario)) {
    throw std::invalid_argument("sim.scenario: unknown scenario '" + name + "' (one of " +
                                scenario_names_text() + ")");
  }
  c.params = params;
  c.seed = seed;
  return c;
}

}  // namespace rovctl::hal::mock
