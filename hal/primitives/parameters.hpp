// Parameter metadata: each parameter is declared once, beside its plain struct, by a describe()
// function that names its key, unit, range and meaning (as PX4's parameter metadata does).
// Loaders (YAML), validators and documentation are visitors over those declarations.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rovctl::hal {

struct ParamMeta {
  std::string_view unit;  // "m", "rad", "ms", "-" (dimensionless), ...
  double min;
  double max;
  std::string_view doc;
  bool required = false;  // no sensible default: the config must give it
};

class ParamVisitor {
 public:
  virtual ~ParamVisitor() = default;

  // A nested mapping `key:`; `body` declares what is inside it.
  virtual void section(std::string_view key, std::string_view doc,
                       const std::function<void(ParamVisitor&)>& body) = 0;

  virtual void param(std::string_view key, double& value, const ParamMeta& meta) = 0;
  virtual void param(std::string_view key, int& value, const ParamMeta& meta) = 0;
  virtual void param(std::string_view key, bool& value, std::string_view doc) = 0;
  // Each component checked against [meta.min, meta.max].
  virtual void param(std::string_view key, Eigen::Vector3d& value, const ParamMeta& meta) = 0;
  // A string; when `choices` is non-empty the value must be one of them.
  virtual void param(std::string_view key, std::string& value, std::string_view doc,
                     const std::vector<std::string>& choices = {}, bool required = false) = 0;
  // A file path; a relative path is resolved against the directory of the config file.
  virtual void path(std::string_view key, std::string& value, std::string_view doc,
                    bool required = false) = 0;
  // A sequence of mappings with [min_count, max_count] elements.
  virtual void list(std::string_view key, std::string_view doc, std::size_t min_count,
                    std::size_t max_count, std::size_t current_count,
                    const std::function<void(std::size_t count)>& resize,
                    const std::function<void(ParamVisitor&, std::size_t index)>& element) = 0;
};

// Declares a list of structs, each described by `describe(visitor, element)`.
template <class T, class Describe>
void param_list(ParamVisitor& v, std::string_view key, std::string_view doc, std::vector<T>& items,
                std::size_t min_count, std::size_t max_count, Describe describe) {
  v.list(
      key, doc, min_count, max_count, items.size(), [&items](std::size_t n) { items.resize(n); },
      [&items, describe](ParamVisitor& inner, std::size_t i) { describe(inner, items[i]); });
}

}  // namespace rovctl::hal
