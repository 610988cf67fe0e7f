// Operator view parameters and the listen address they name.
#include "app/runtime/operator_view_params.hpp"

#include <cstdlib>

namespace rovctl::app {

void describe(hal::ParamVisitor& v, OperatorViewParams& p) {
  v.param("listen", p.listen,
          "HOST:PORT of the live operator view (cameras, estimate, mission, ABORT); empty: off. "
          "127.0.0.1 keeps it on the vehicle; any other address is reachable from the network "
          "(rovctl check warns)");
  v.param("token", p.token,
          "shared secret the page must send with ABORT and START (header X-Rovctl-Token); empty: "
          "the view is read-only");
  v.param("frame_rate_hz", p.frame_rate_hz,
          {"Hz", 0.5, 30.0,
           "how often the tick copies the camera images for the view (and the view encodes them)"});
  v.param("jpeg_quality", p.jpeg_quality, {"-", 10, 100, "JPEG quality of the camera stream"});
  v.param("max_streams", p.max_streams,
          {"streams", 1, 256,
           "live streams (camera or events; a browser tab holds two) served at once, each on its "
           "own thread below the tick's priority; the next is refused with 503. ABORT, START and "
           "the pages never count against it"});
  v.param("command_max_age_ms", p.command_max_age_ms,
          {"ms", 20.0, 2000.0,
           "ABORT or START is carried out at once or never: one older than this (from its "
           "request's first byte), whose client has gone, or that no tick took within it, is "
           "dropped, logged and answered 503, never applied later"});
}

bool ListenAddress::loopback() const {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

bool parse_listen_address(const std::string& text, ListenAddress& out, std::string& error) {
  std::string host;
  std::string port;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string::npos || close + 1 >= text.size() || text[close + 1] != ':') {
      error = "'" + text + "' is not [IPV6]:PORT";
      return false;
    }
    host = text.substr(1, close - 1);
    port = text.substr(close + 2);
  } else {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) {
      error = "'" + text + "' is not HOST:PORT (for example 127.0.0.1:8080)";
      return false;
    }
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
  }
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || end == nullptr || *end != '\0' || p < 0 || p > 65535) {
    error = "'" + text + "': the port must be 0-65535 (0: any free port)";
    return false;
  }
  out.host = host;
  out.port = static_cast<int>(p);
  return true;
}

}  // namespace rovctl::app
