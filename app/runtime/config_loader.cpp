// YAML visitor behind the declared parameters, and the documentation visitor.
#include "app/runtime/config_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "app/runtime/errors.hpp"
#include "hal/primitives/number_format.hpp"

namespace rovctl::app {
namespace {

class YamlLoader final : public hal::ParamVisitor {
 public:
  YamlLoader(YAML::Node node, std::string prefix, const std::string& file,
             const std::string& base_dir, KeyLines* lines)
      : node_(std::move(node)),
        prefix_(std::move(prefix)),
        file_(file),
        base_dir_(base_dir),
        lines_(lines) {}

  void section(std::string_view key, std::string_view,
               const std::function<void(hal::ParamVisitor&)>& body) override {
    const YAML::Node n = child(key);
    if (n && !n.IsNull() && !n.IsMap()) fail(n, key, "expected a mapping");
    YamlLoader inner(n && n.IsMap() ? n : YAML::Node(), path_of(key), file_, base_dir_, lines_);
    inner.line_ = n ? n.Mark().line + 1 : line_;
    body(inner);
    inner.finish();
  }

  void param(std::string_view key, double& value, const hal::ParamMeta& meta) override {
    const YAML::Node n = child(key);
    if (!present(n, key, meta.required)) return;
    value = scalar<double>(n, key, "a number");
    check_range(n, key, value, meta);
  }

  void param(std::string_view key, int& value, const hal::ParamMeta& meta) override {
    const YAML::Node n = child(key);
    if (!present(n, key, meta.required)) return;
    value = scalar<int>(n, key, "an integer");
    check_range(n, key, value, meta);
  }

  void param(std::string_view key, bool& value, std::string_view) override {
    const YAML::Node n = child(key);
    if (!present(n, key, false)) return;
    value = scalar<bool>(n, key, "true or false");
  }

  void param(std::string_view key, Eigen::Vector3d& value, const hal::ParamMeta& meta) override {
    const YAML::Node n = child(key);
    if (!present(n, key, meta.required)) return;
    if (!n.IsSequence() || n.size() != 3) fail(n, key, "expected a list of 3 numbers [x, y, z]");
    for (int i = 0; i < 3; ++i) {
      try {
        value[i] = n[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(n, key,
             "expected a list of 3 numbers, element " + std::to_string(i) + " is '" +
                 n[i].Scalar() + "'");
      }
      check_range(n, key, value[i], meta);
    }
  }

  void param(std::string_view key, std::string& value, std::string_view,
             const std::vector<std::string>& choices, bool required) override {
    const YAML::Node n = child(key);
    if (!present(n, key, required)) return;
    const std::string v = scalar<std::string>(n, key, "a string");
    if (!choices.empty()) {
      bool ok = false;
      std::string all;
      for (const auto& c : choices) {
        ok = ok || c == v;
        all += (all.empty() ? "" : ", ") + c;
      }
      if (!ok) fail(n, key, "'" + v + "' is not one of: " + all);
    }
    value = v;
  }

  void path(std::string_view key, std::string& value, std::string_view, bool required) override {
    const YAML::Node n = child(key);
    if (!present(n, key, required)) return;
    const std::string v = scalar<std::string>(n, key, "a file path");
    if (v.empty()) fail(n, key, "empty path");
    const std::filesystem::path p(v);
    value =
        p.is_absolute() || base_dir_.empty() ? v : (std::filesystem::path(base_dir_) / p).string();
  }

  void list(std::string_view key, std::string_view, std::size_t min_count, std::size_t max_count,
            std::size_t, const std::function<void(std::size_t)>& resize,
            const std::function<void(hal::ParamVisitor&, std::size_t)>& element) override {
    const YAML::Node n = child(key);
    if (!present(n, key, false)) return;
    if (!n.IsSequence()) fail(n, key, "expected a list");
    if (n.size() < min_count || n.size() > max_count) {
      fail(n, key,
           "expected " + std::to_string(min_count) + " to " + std::to_string(max_count) +
               " elements, got " + std::to_string(n.size()));
    }
    resize(n.size());
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node e = n[i];
      const std::string name = path_of(key) + "[" + std::to_string(i) + "]";
      if (!e.IsMap()) fail(e, key, "element " + std::to_string(i) + ": expected a mapping");
      YamlLoader inner(e, name, file_, base_dir_, lines_);
      inner.line_ = e.Mark().line + 1;
      if (lines_ != nullptr) (*lines_)[name] = inner.line_;
      element(inner, i);
      inner.finish();
    }
  }

  // Every key present must have been declared, and given once: YAML parsers keep the first of
  // two equal keys and drop the second without a word, so an edited value could silently lose.
  void finish() const {
    if (!node_ || !node_.IsMap()) return;
    std::set<std::string> present;
    for (const auto& kv : node_) {
      const std::string key = kv.first.as<std::string>();
      if (!present.insert(key).second) {
        fail(kv.first, key,
             "given twice (the first is line " + std::to_string(line_of_key(key)) + ")");
      }
      if (seen_.count(key) == 0) fail(kv.first, key, "unknown key");
    }
  }

  int line_ = 0;

 private:
  YAML::Node child(std::string_view key) {
    seen_.insert(std::string(key));
    if (!node_ || !node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node& const_node = node_;
    const YAML::Node n = const_node[std::string(key)];
    if (lines_ != nullptr && n.IsDefined() && !n.Mark().is_null()) {
      (*lines_)[path_of(key)] = line_of_key(key);
    }
    return n;
  }

  // The line of the key itself (a block mapping's value starts on the line after it).
  int line_of_key(std::string_view key) const {
    for (const auto& kv : node_) {
      if (kv.first.as<std::string>() == key) return kv.first.Mark().line + 1;
    }
    return line_;
  }

  bool present(const YAML::Node& n, std::string_view key, bool required) const {
    if (n.IsDefined() && !n.IsNull()) return true;
    if (required) {
      throw ConfigError(file_ + ":" + std::to_string(line_) + ": " + path_of(key) +
                        ": missing required key");
    }
    return false;
  }

  template <class T>
  T scalar(const YAML::Node& n, std::string_view key, const char* expected) const {
    if (!n.IsScalar()) fail(n, key, std::string("expected ") + expected);
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      fail(n, key, std::string("expected ") + expected + ", got '" + n.Scalar() + "'");
    }
  }

  template <class T>
  void check_range(const YAML::Node& n, std::string_view key, T v, const hal::ParamMeta& m) const {
    const double d = static_cast<double>(v);
    if (!std::isfinite(d) || d < m.min || d > m.max) {
      fail(n, key,
           hal::format_number(d) + " is out of range [" + hal::format_number(m.min) + ", " +
               hal::format_number(m.max) + "] " + std::string(m.unit));
    }
  }

  [[noreturn]] void fail(const YAML::Node& n, std::string_view key, const std::string& what) const {
    const int line = n.Mark().is_null() ? line_ : n.Mark().line + 1;
    throw ConfigError(file_ + ":" + std::to_string(line) + ": " + path_of(key) + ": " + what);
  }

  std::string path_of(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }

  YAML::Node node_;
  std::string prefix_;
  const std::string& file_;
  const std::string& base_dir_;
  KeyLines* lines_;
  std::set<std::string> seen_;
};

void load_node(const YAML::Node& root, const std::string& name, const std::string& base_dir,
               const std::function<void(hal::ParamVisitor&)>& describe, KeyLines* lines) {
  if (root && !root.IsNull() && !root.IsMap()) {
    throw ConfigError(name + ":1: the top level must be a mapping of sections");
  }
  YamlLoader loader(root, "", name, base_dir, lines);
  loader.line_ = 1;
  describe(loader);
  loader.finish();
}

class DocVisitor final : public hal::ParamVisitor {
 public:
  explicit DocVisitor(std::ostringstream& out, std::string prefix = "")
      : out_(out), prefix_(std::move(prefix)) {}

  void section(std::string_view key, std::string_view doc,
               const std::function<void(hal::ParamVisitor&)>& body) override {
    out_ << "| `" << path_of(key) << "` | section | | | | " << doc << " |\n";
    DocVisitor inner(out_, path_of(key));
    body(inner);
  }
  void param(std::string_view key, double& value, const hal::ParamMeta& m) override {
    row(key, "number", m, hal::format_number(value));
  }
  void param(std::string_view key, int& value, const hal::ParamMeta& m) override {
    row(key, "integer", m, std::to_string(value));
  }
  void param(std::string_view key, bool& value, std::string_view doc) override {
    out_ << "| `" << path_of(key) << "` | bool | | | " << (value ? "true" : "false") << " | " << doc
         << " |\n";
  }
  void param(std::string_view key, Eigen::Vector3d& v, const hal::ParamMeta& m) override {
    row(key, "[x, y, z]", m,
        "[" + hal::format_number(v.x()) + ", " + hal::format_number(v.y()) + ", " +
            hal::format_number(v.z()) + "]");
  }
  void param(std::string_view key, std::string& value, std::string_view doc,
             const std::vector<std::string>& choices, bool required) override {
    std::string all;
    for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
    out_ << "| `" << path_of(key) << "` | string | | " << all << " | "
         << (required ? "(required)" : value) << " | " << doc << " |\n";
  }
  void path(std::string_view key, std::string& value, std::string_view doc,
            bool required) override {
    out_ << "| `" << path_of(key) << "` | path | | | " << (required ? "(required)" : value) << " | "
         << doc << " |\n";
  }
  void list(std::string_view key, std::string_view doc, std::size_t min_count,
            std::size_t max_count, std::size_t current_count,
            const std::function<void(std::size_t)>&,
            const std::function<void(hal::ParamVisitor&, std::size_t)>& element) override {
    out_ << "| `" << path_of(key) << "[]` | list | | " << min_count << "-" << max_count << " | "
         << current_count << " elements | " << doc << " |\n";
    if (current_count > 0) {
      DocVisitor inner(out_, path_of(key) + "[]");
      element(inner, 0);
    }
  }

 private:
  void row(std::string_view key, const char* type, const hal::ParamMeta& m,
           const std::string& def) {
    out_ << "| `" << path_of(key) << "` | " << type << " | " << m.unit << " | "
         << hal::format_number(m.min) << " .. " << hal::format_number(m.max) << " | "
         << (m.required ? "(required)" : def) << " | " << m.doc << " |\n";
  }
  std::string path_of(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  std::ostringstream& out_;
  std::string prefix_;
};

}  // namespace

void load_yaml_file(const std::string& file,
                    const std::function<void(hal::ParamVisitor&)>& describe, KeyLines* lines) {
  if (!std::filesystem::is_regular_file(file)) {
    throw ConfigError(file + ": cannot read config file (no such file)");
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(file + ":" + std::to_string(e.mark.line + 1) +
                      ": YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ConfigError(file + ": cannot read config file: " + e.msg);
  }
  const std::string base_dir = std::filesystem::path(file).parent_path().string();
  load_node(root, file, base_dir, describe, lines);
}

void load_yaml_text(const std::string& text, const std::string& name, const std::string& base_dir,
                    const std::function<void(hal::ParamVisitor&)>& describe, KeyLines* lines) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(name + ":" + std::to_string(e.mark.line + 1) +
                      ": YAML syntax error: " + e.msg);
  }
  load_node(root, name, base_dir, describe, lines);
}

std::string describe_parameters_markdown(const std::function<void(hal::ParamVisitor&)>& describe) {
  std::ostringstream out;
  out << "| key | type | unit | range | default | meaning |\n|---|---|---|---|---|---|\n";
  DocVisitor doc(out);
  describe(doc);
  return out.str();
}

}  // namespace rovctl::app
