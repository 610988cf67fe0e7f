// Server routes, the pump that turns the link's latest tick into JSON and JPEG, and the streams.
// The pump and the stream and page threads run below the tick (run_below_the_tick); commands
// are served by ViewHttpServer's command thread, which no viewer can occupy.
#include "app/view/operator_view.hpp"

#include <httplib.h>
#include <sys/socket.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "app/tools/json_writer.hpp"
#include "app/view/background_priority.hpp"
#include "app/view/estimate_overlay.hpp"
#include "app/view/operator_page.hpp"
#include "app/view/operator_state.hpp"
#include "app/view/view_http_server.hpp"

namespace rovctl::app {
namespace {

constexpr auto kStatePeriod = std::chrono::milliseconds(50);
constexpr auto kKeepAlive = std::chrono::seconds(1);
constexpr const char* kBoundary = "rovctlframe";

Eigen::Isometry3d pose_of(const TelemetryRecord& r) {
  const Eigen::Quaterniond q(r.est_q_wxyz[0], r.est_q_wxyz[1], r.est_q_wxyz[2], r.est_q_wxyz[3]);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(r.est_t_m[0], r.est_t_m[1], r.est_t_m[2]);
  return T;
}

// Constant time in the token's length, so response timing does not reveal a prefix.
bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

OperatorView::OperatorView(const OperatorViewParams& params, const hal::StereoRig& rig,
                           const hal::MarkerModel& marker, OperatorLink& link,
                           OperatorViewOptions options)
    : params_(params), rig_(rig), marker_(marker), link_(link), options_(std::move(options)) {
  ViewHttpLimits limits;
  limits.max_streams = params_.max_streams;
  server_ =
      std::make_unique<ViewHttpServer>(limits, [](std::string_view method, std::string_view path) {
        if (method == "POST" && (path == "/abort" || path == "/start")) return RequestKind::command;
        if (method == "GET" && (path == "/events" || path == "/stream.mjpg"))
          return RequestKind::stream;
        return RequestKind::page;
      });
}

OperatorView::~OperatorView() { stop(); }

std::string OperatorView::url() const {
  const bool v6 = host_.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + host_ + "]" : host_) + ":" + std::to_string(port_) + "/";
}

namespace {

// A stream with nothing new to send learns here that its viewer left (else only at its next
// write), so the stream thread is free again.
bool client_gone() {
  const ViewRequestInfo* info = ViewHttpServer::current();
  return info != nullptr && info->client_gone();
}

}  // namespace

int OperatorView::streams_open() const { return server_->streams_open(); }
std::uint64_t OperatorView::streams_refused() const { return server_->streams_refused(); }

std::string OperatorView::exposure() const {
  const bool replay = std::string_view(options_.source) == "replay";
  const std::string commands = replay ? "read-only: a replay takes no commands"
                               : params_.token.empty()
                                   ? "read-only: no token, ABORT and START are refused"
                                   : "commands enabled: whoever has the token can ABORT and START";
  ListenAddress address;
  address.host = host_;
  if (address.loopback()) return "operator view on this machine only (" + host_ + "); " + commands;
  const bool every = host_ == "0.0.0.0" || host_ == "::" || host_.empty();
  return "warning: the operator view listens on " +
         (every ? std::string("every address of this machine") : host_) + " port " +
         std::to_string(port_) +
         ": anyone who can reach it sees the cameras and the mission, without a login; " + commands;
}

bool OperatorView::authorised(const std::string& token) const {
  return !params_.token.empty() && same_secret(token, params_.token);
}

void OperatorView::routes() {
  httplib::Server& s = *server_;
  s.Get("/", [](const httplib::Request&, httplib::Response& res) {
    const std::string_view page = operator_page_html();
    res.set_content(page.data(), page.size(), "text/html; charset=utf-8");
  });
  s.Get("/info", [this](const httplib::Request&, httplib::Response& res) {
    JsonWriter w;
    w.begin_object()
        .field("source", options_.source)
        .field("images", options_.images)
        .field("commands_enabled", !params_.token.empty())
        .end_object();
    res.set_content(w.str(), "application/json");
  });
  s.Get("/state", [this](const httplib::Request&, httplib::Response& res) {
    std::shared_ptr<const std::string> state;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      state = state_json_;
    }
    if (!state) {
      res.status = 503;
      res.set_content("{\"error\": \"no tick published yet\"}", "application/json");
      return;
    }
    res.set_header("Cache-Control", "no-cache");
    res.set_content(*state, "application/json");
  });
  s.Get("/events", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    auto seen = std::make_shared<std::uint64_t>(0);
    res.set_content_provider(
        "text/event-stream", [this, seen](std::size_t, httplib::DataSink& sink) {
          std::shared_ptr<const std::string> state;
          {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait_for(lock, kKeepAlive,
                              [&] { return stopping_ || (state_seq_ != *seen && state_json_); });
            if (stopping_) return false;
            if (state_seq_ != *seen) {
              *seen = state_seq_;
              state = state_json_;
            }
          }
          const std::string msg = state ? "data: " + *state + "\n\n" : std::string(": alive\n\n");
          return sink.write(msg.data(), msg.size());
        });
  });
  s.Get("/stream.mjpg", [this](const httplib::Request&, httplib::Response& res) {
    if (!options_.images) {
      res.status = 404;
      res.set_content("no camera images in this source", "text/plain");
      return;
    }
    res.set_header("Cache-Control", "no-cache");
    auto seen = std::make_shared<std::uint64_t>(0);
    res.set_content_provider(
        std::string("multipart/x-mixed-replace; boundary=") + kBoundary,
        [this, seen](std::size_t, httplib::DataSink& sink) {
          std::shared_ptr<const std::string> jpeg;
          {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait_for(lock, kKeepAlive,
                              [&] { return stopping_ || (frame_seq_ != *seen && jpeg_); });
            if (stopping_) return false;
            if (frame_seq_ == *seen || !jpeg_) return !client_gone();  // nothing new: wait again
            *seen = frame_seq_;
            jpeg = jpeg_;
          }
          // Always the newest picture: a client too slow for every frame skips the ones between.
          const std::string head =
              std::string("--") + kBoundary +
              "\r\nContent-Type: image/jpeg\r\nContent-Length: " + std::to_string(jpeg->size()) +
              "\r\n\r\n";
          return sink.write(head.data(), head.size()) && sink.write(jpeg->data(), jpeg->size()) &&
                 sink.write("\r\n", 2);
        });
  });
  s.Get("/snapshot.jpg", [this](const httplib::Request&, httplib::Response& res) {
    std::shared_ptr<const std::string> jpeg;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      jpeg = jpeg_;
    }
    if (!jpeg) {
      res.status = 503;
      res.set_content("no picture yet", "text/plain");
      return;
    }
    res.set_content(*jpeg, "image/jpeg");
  });
  const auto command = [this](const char* name, OperatorCommand which) {
    return [this, name, which](const httplib::Request& req, httplib::Response& res) {
      if (params_.token.empty()) {
        ++refused_;
        res.status = 403;
        res.set_content("refused: no operator_view.token is configured, the view is read-only",
                        "text/plain");
        return;
      }
      if (!authorised(req.get_header_value("X-Rovctl-Token"))) {
        ++refused_;
        std::cerr << "rovctl: operator view: " << name << " from " << req.remote_addr
                  << " refused (wrong or missing token)\n";
        res.status = 403;
        res.set_content("refused: wrong or missing X-Rovctl-Token", "text/plain");
        return;
      }
      // At once or never: an operator who saw a command fail (or gave up on it) must not see it
      // run later, so an old request, one whose client has gone, or one no tick takes within
      // the bound is dropped here and withdrawn from the link.
      const auto max_age = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double, std::milli>(params_.command_max_age_ms));
      const ViewRequestInfo* info = ViewHttpServer::current();
      const auto now = std::chrono::steady_clock::now();
      const auto received = info != nullptr ? info->received_at : now;
      const double waited_ms = std::chrono::duration<double, std::milli>(now - received).count();
      char bound[32];
      std::snprintf(bound, sizeof(bound), "%.0f ms", params_.command_max_age_ms);
      std::string why;
      OperatorCommandResult result;
      if (now - received > max_age) {
        char text[96];
        std::snprintf(text, sizeof(text), "it waited %.0f ms, over ", waited_ms);
        why = text + std::string(bound) + " (operator_view.command_max_age_ms)";
      } else if (info != nullptr && info->client_gone()) {
        why = "its client has gone";
      } else {
        result = link_.submit(which, received + max_age);
        if (!result.taken) {
          why = "no tick took it within " + std::string(bound) +
                " of its request (operator_view.command_max_age_ms)";
        }
      }
      if (!result.taken) {
        ++dropped_;
        std::cerr << "rovctl: operator view: " << name << " from " << req.remote_addr
                  << " dropped, not applied: " << why << "\n";
        res.status = 503;
        res.set_content(std::string(name) + " not applied: " + why, "text/plain");
        return;
      }
      if (which == OperatorCommand::abort) abort_tick_.store(result.tick == 0 ? 1 : result.tick);
      std::cerr << "rovctl: operator view: " << name << " from " << req.remote_addr
                << " taken at tick " << result.tick << "\n";
      JsonWriter w;
      w.begin_object()
          .field("accepted", name)
          .field("tick", static_cast<long>(result.tick))
          .end_object();
      res.set_content(w.str(), "application/json");
    };
  };
  s.Post("/abort", command("ABORT", OperatorCommand::abort));
  s.Post("/start", command("START", OperatorCommand::start));
  // BlueOS lists and embeds services that answer this (name, icon, the page to open).
  s.Get("/register_service", [this](const httplib::Request&, httplib::Response& res) {
    JsonWriter w;
    w.begin_object()
        .field("name", "rovctl operator view")
        .field("description", "Live stereo cameras, marker estimate and docking mission of rovctl")
        .field("icon", "mdi-submarine")
        .field("company", "rovctl")
        .field("version", options_.version.empty() ? "dev" : options_.version)
        .field("webpage", "/")
        .field("api", "/state")
        .field("works_in_relative_paths", true)
        .end_object();
    res.set_content(w.str(), "application/json");
  });
}

bool OperatorView::start(std::string& error) {
  if (running_) return true;
  ListenAddress address;
  if (!parse_listen_address(params_.listen, address, error)) {
    error = "operator_view.listen: " + error;
    return false;
  }
  host_ = address.host;
  server_->set_write_timeout(std::chrono::seconds(2));
  // httplib's default is SO_REUSEPORT, which lets a second rovctl bind the same port and share
  // its clients (ABORT included) unnoticed: only SO_REUSEADDR here, so a busy port is an error.
  server_->set_socket_options([](int sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  routes();
  if (address.port == 0) {
    port_ = server_->bind_to_any_port(address.host);
  } else if (server_->bind_to_port(address.host, address.port)) {
    port_ = address.port;
  } else {
    port_ = -1;
  }
  if (port_ <= 0) {
    error = "operator view: cannot listen on " + params_.listen +
            " (address in use, or not an address of this machine)";
    return false;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = false;
  }
  if (!server_->start_dispatch(run_below_the_tick, error)) return false;
  running_ = true;
  pump_thread_ = std::thread([this] {
    run_below_the_tick();  // the JPEG encoding, once per frame whatever the number of viewers
    pump();
  });
  server_thread_ = std::thread([this] { server_->listen_after_bind(); });
  // httplib's stop() is a no-op until the listen loop runs: wait for it, so that a stop() right
  // after start() cannot leave the listen thread blocked forever.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!server_->is_running() && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (!server_->is_running()) {
    stop();
    error = "operator view: the server on " + params_.listen + " did not start";
    return false;
  }
  return true;
}

void OperatorView::stop() {
  if (!running_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  server_->stop();
  if (server_thread_.joinable()) server_thread_.join();
  server_->stop_dispatch();
  if (pump_thread_.joinable()) pump_thread_.join();
  running_ = false;
}

void OperatorView::pump() {
  const auto frame_period = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(1.0 / params_.frame_rate_hz));
  const std::vector<int> jpeg_params{cv::IMWRITE_JPEG_QUALITY, params_.jpeg_quality};
  cv::Mat composite;
  std::vector<uchar> encoded;
  OperatorStateContext context;
  context.source = options_.source;
  context.commands_enabled = !params_.token.empty();
  auto next_frame = std::chrono::steady_clock::now();
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait_for(lock, kStatePeriod, [this] { return stopping_; });
      if (stopping_) return;
    }
    context.abort_requested_tick = abort_tick_.load();
    if (const TelemetryRecord* r = link_.records().take()) {
      auto json = std::make_shared<const std::string>(operator_state_json(*r, context));
      {
        std::lock_guard<std::mutex> lock(mutex_);
        state_json_ = std::move(json);
        ++state_seq_;
      }
      changed_.notify_all();
    }
    const auto now = std::chrono::steady_clock::now();
    if (!options_.images || now < next_frame) continue;
    const OperatorFrame* f = link_.frames().take();
    if (f == nullptr) continue;
    next_frame = now + frame_period;
    cv::hconcat(f->left_bgr, f->right_bgr, composite);
    if ((f->record.flags & telemetry_flag::estimate_valid) != 0) {
      const bool ok = (f->record.flags & telemetry_flag::full_view) != 0;
      const Eigen::Isometry3d T_cl_marker = pose_of(f->record);
      cv::Mat left = composite(cv::Rect(0, 0, f->left_bgr.cols, f->left_bgr.rows));
      cv::Mat right =
          composite(cv::Rect(f->left_bgr.cols, 0, f->right_bgr.cols, f->right_bgr.rows));
      draw_estimate_overlay(left, rig_.left, marker_, T_cl_marker, ok);
      draw_estimate_overlay(right, rig_.right, marker_, rig_.T_cr_cl * T_cl_marker, ok);
    }
    if (!cv::imencode(".jpg", composite, encoded, jpeg_params)) continue;
    auto jpeg = std::make_shared<const std::string>(encoded.begin(), encoded.end());
    {
      std::lock_guard<std::mutex> lock(mutex_);
      jpeg_ = std::move(jpeg);
      ++frame_seq_;
    }
    ++frames_encoded_;
    changed_.notify_all();
  }
}

}  // namespace rovctl::app
