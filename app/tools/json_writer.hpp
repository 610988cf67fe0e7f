// A tiny JSON emitter for the CLI's --json outputs: one object, built in order, no dependencies.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rovctl::app {

class JsonWriter {
 public:
  JsonWriter& begin_object(std::string_view key = {});
  JsonWriter& end_object();
  JsonWriter& begin_array(std::string_view key = {});
  JsonWriter& end_array();
  JsonWriter& field(std::string_view key, double value);  // non-finite -> null
  JsonWriter& field(std::string_view key, long value);
  JsonWriter& field(std::string_view key, int value) {
    return field(key, static_cast<long>(value));
  }
  JsonWriter& field(std::string_view key, bool value);
  JsonWriter& field(std::string_view key, std::string_view value);
  // Without it a string literal would convert to bool, not to string_view.
  JsonWriter& field(std::string_view key, const char* value) {
    return field(key, std::string_view(value));
  }
  JsonWriter& value(double value);  // an array element

  const std::string& str() const { return out_; }

 private:
  void prefix(std::string_view key);
  std::string out_;
  std::vector<bool> first_;  // per open container: nothing written in it yet
};

std::string json_escape(std::string_view text);

}  // namespace rovctl::app
