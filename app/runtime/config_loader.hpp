// Loads declared parameters (hal::ParamVisitor) from YAML, strictly: unknown keys, missing
// required keys, wrong types and out-of-range values are ConfigErrors naming file, line and key.
#pragma once

#include <functional>
#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

// Parses `file` and visits `describe` over its top-level mapping. Throws ConfigError.
void load_yaml_file(const std::string& file,
                    const std::function<void(hal::ParamVisitor&)>& describe);

// The same over YAML text; relative paths are resolved against `base_dir`. For tests.
void load_yaml_text(const std::string& text, const std::string& name, const std::string& base_dir,
                    const std::function<void(hal::ParamVisitor&)>& describe);

// Markdown table of every declared parameter: key, type, unit, range, default, meaning.
std::string describe_parameters_markdown(const std::function<void(hal::ParamVisitor&)>& describe);

}  // namespace rovctl::app
