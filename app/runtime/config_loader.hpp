// Loads declared parameters (hal::ParamVisitor) from YAML, strictly: unknown keys, missing
// required keys, wrong types and out-of-range values are ConfigErrors naming file, line and key.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

// Where each key given in a file sits: its dotted path ("vehicle.thrusters",
// "marker.spheres[1].centre_m") -> 1-based line. Checks that run after loading (cross-field,
// layout, marker) name the line of the key they reject from it.
using KeyLines = std::map<std::string, int>;

// Parses `file` and visits `describe` over its top-level mapping. Throws ConfigError. With
// `lines`, records the line of every key present.
void load_yaml_file(const std::string& file,
                    const std::function<void(hal::ParamVisitor&)>& describe,
                    KeyLines* lines = nullptr);

// The same over YAML text; relative paths are resolved against `base_dir`. For tests.
void load_yaml_text(const std::string& text, const std::string& name, const std::string& base_dir,
                    const std::function<void(hal::ParamVisitor&)>& describe,
                    KeyLines* lines = nullptr);

// Markdown table of every declared parameter: key, type, unit, range, default, meaning.
std::string describe_parameters_markdown(const std::function<void(hal::ParamVisitor&)>& describe);

}  // namespace rovctl::app
