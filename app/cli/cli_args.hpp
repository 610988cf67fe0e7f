// Command-line options of one rovctl sub-command: `--name value` options and `--flag` flags.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace rovctl::app {

class CliArgs {
 public:
  // Throws UsageError naming the command and the offending word.
  static CliArgs parse(const std::string& command, const std::vector<std::string>& words,
                       const std::set<std::string>& options, const std::set<std::string>& flags);

  bool has(const std::string& name) const;
  // The last value given (get), or every value in order (all: a repeatable option).
  std::string get(const std::string& name, const std::string& fallback = "") const;
  std::vector<std::string> all(const std::string& name) const;
  long get_int(const std::string& name, long fallback, long min, long max) const;
  double get_double(const std::string& name, double fallback, double min, double max) const;
  // A comma-separated value (`--only a,b`): its items in order, none if the option is absent.
  // An empty item (`a,,b`, `a,`, an empty value) is a usage error naming the option.
  std::vector<std::string> get_list(const std::string& name) const;
  // A comma list of numbers (`--range-bands-m 0.5,1.0,1.3`), strictly ascending, each finite and in
  // (above, at_most]; a bad one is a usage error naming the option, its value, `what` it must be
  // and the item. None if the option is absent.
  std::vector<double> get_ascending(const std::string& name, double above, double at_most,
                                    const std::string& what) const;

 private:
  std::string command_;
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> repeated_;
};

}  // namespace rovctl::app
