// The operator view's configuration: where its HTTP server listens, the token that guards ABORT
// and START, how often it shows the cameras, how many may watch, and how fresh a command must be.
// Off unless `listen` is set.
#pragma once

#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

struct OperatorViewParams {
  std::string listen;  // "HOST:PORT"; empty: no operator view
  std::string token;   // required by POST /abort and /start; empty: commands refused
  double frame_rate_hz = 10.0;
  int jpeg_quality = 70;
  int max_streams = 16;
  double command_max_age_ms = 250.0;

  bool enabled() const { return !listen.empty(); }
};

void describe(hal::ParamVisitor& v, OperatorViewParams& p);

struct ListenAddress {
  std::string host;
  int port = 0;
  bool loopback() const;  // 127.0.0.0/8, ::1 or localhost
};

// Parses "HOST:PORT" (IPv4, [IPv6] or a name; port 0-65535, 0: any free port); false with `error`
// on a bad one.
bool parse_listen_address(const std::string& text, ListenAddress& out, std::string& error);

}  // namespace rovctl::app
