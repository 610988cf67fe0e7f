// JSON text with commas managed per open container; numbers with up to 10 significant digits.
#include "app/tools/json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace rovctl::app {

std::string json_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

void JsonWriter::prefix(std::string_view key) {
  if (!first_.empty()) {
    if (!first_.back()) out_ += ", ";
    first_.back() = false;
  }
  if (!key.empty()) out_ += "\"" + json_escape(key) + "\": ";
}

JsonWriter& JsonWriter::begin_object(std::string_view key) {
  prefix(key);
  out_ += "{";
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  out_ += "}";
  first_.pop_back();
  return *this;
}

JsonWriter& JsonWriter::begin_array(std::string_view key) {
  prefix(key);
  out_ += "[";
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  out_ += "]";
  first_.pop_back();
  return *this;
}

JsonWriter& JsonWriter::value(double v) {
  prefix({});
  if (!std::isfinite(v)) {
    out_ += "null";
  } else {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    out_ += buf;
  }
  return *this;
}

JsonWriter& JsonWriter::field(std::string_view key, double v) {
  prefix(key);
  first_.push_back(true);  // value() must not add a comma after the key
  value(v);
  first_.pop_back();
  return *this;
}

JsonWriter& JsonWriter::field(std::string_view key, long v) {
  prefix(key);
  out_ += std::to_string(v);
  return *this;
}

JsonWriter& JsonWriter::field(std::string_view key, bool v) {
  prefix(key);
  out_ += v ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::field(std::string_view key, std::string_view v) {
  prefix(key);
  out_ += "\"" + json_escape(v) + "\"";
  return *this;
}

}  // namespace rovctl::app
