// Strict option parsing: unknown options, missing values and bad numbers are usage errors.
#include "app/cli/cli_args.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "app/runtime/errors.hpp"

namespace rovctl::app {

CliArgs CliArgs::parse(const std::string& command, const std::vector<std::string>& words,
                       const std::set<std::string>& options, const std::set<std::string>& flags) {
  CliArgs args;
  args.command_ = command;
  for (std::size_t i = 0; i < words.size(); ++i) {
    std::string word = words[i];
    std::string value;
    bool has_inline_value = false;
    if (const auto eq = word.find('='); word.rfind("--", 0) == 0 && eq != std::string::npos) {
      value = word.substr(eq + 1);
      word = word.substr(0, eq);
      has_inline_value = true;
    }
    if (flags.count(word) != 0 && !has_inline_value) {
      args.values_[word] = "1";
    } else if (options.count(word) != 0) {
      if (!has_inline_value) {
        if (i + 1 >= words.size()) {
          throw UsageError("rovctl " + command + ": option " + word + " needs a value");
        }
        value = words[++i];
      }
      args.values_[word] = value;
      args.repeated_[word].push_back(value);
    } else {
      throw UsageError("rovctl " + command + ": unknown option '" + word + "' (see rovctl help)");
    }
  }
  return args;
}

bool CliArgs::has(const std::string& name) const { return values_.count(name) != 0; }

std::string CliArgs::get(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

std::vector<std::string> CliArgs::all(const std::string& name) const {
  const auto it = repeated_.find(name);
  return it == repeated_.end() ? std::vector<std::string>{} : it->second;
}

long CliArgs::get_int(const std::string& name, long fallback, long min, long max) const {
  if (!has(name)) return fallback;
  const std::string text = get(name);
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < min || v > max) {
    throw UsageError("rovctl " + command_ + ": " + name + " must be an integer in [" +
                     std::to_string(min) + ", " + std::to_string(max) + "], got '" + text + "'");
  }
  return v;
}

double CliArgs::get_double(const std::string& name, double fallback, double min, double max) const {
  if (!has(name)) return fallback;
  const std::string text = get(name);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v >= min && v <= max)) {
    throw UsageError("rovctl " + command_ + ": " + name + " must be a number in [" +
                     std::to_string(min) + ", " + std::to_string(max) + "], got '" + text + "'");
  }
  return v;
}

std::vector<std::string> CliArgs::get_list(const std::string& name) const {
  std::vector<std::string> items;
  if (!has(name)) return items;
  const std::string text = get(name);
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    items.push_back(text.substr(start, comma - start));
    if (items.back().empty()) {
      throw UsageError("rovctl " + command_ + ": " + name +
                       " must be items separated by single commas, got '" + text +
                       "' (an empty item at character " + std::to_string(start + 1) + ")");
    }
    start = comma + 1;
  }
  return items;
}

std::vector<double> CliArgs::get_ascending(const std::string& name, double above, double at_most,
                                           const std::string& what) const {
  std::vector<double> numbers;
  for (const std::string& item : get_list(name)) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (*end != '\0' || !std::isfinite(v) || !(v > above && v <= at_most) ||
        (!numbers.empty() && !(v > numbers.back()))) {
      throw UsageError("rovctl " + command_ + ": " + name + " " + get(name) + ": must be " + what +
                       " separated by commas (at '" + item + "')");
    }
    numbers.push_back(v);
  }
  return numbers;
}

}  // namespace rovctl::app
