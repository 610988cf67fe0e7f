// The live operator view: an HTTP server on its own threads (never the tick's) that shows what
// the vehicle sees and believes — the cameras with the estimate drawn on them as an MJPEG
// stream, the latest telemetry as JSON and Server-Sent Events — and takes ABORT and START with
// the configured token. Reads the tick only through an OperatorLink, so a slow or vanished
// browser drops frames and never delays a tick; commands travel on a path no viewer shares, and
// a command is carried out at once (a tick takes it within operator_view.command_max_age_ms) or
// never.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "app/runtime/operator_link.hpp"
#include "app/runtime/operator_view_params.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

class ViewHttpServer;

struct OperatorViewOptions {
  const char* source = "live";  // "live" or "replay" (shown on the page)
  bool images = true;           // the link carries camera images
  std::string version;          // for /register_service
};

class OperatorView {
 public:
  OperatorView(const OperatorViewParams& params, const hal::StereoRig& rig,
               const hal::MarkerModel& marker, OperatorLink& link,
               OperatorViewOptions options = {});
  ~OperatorView();  // stop()
  OperatorView(const OperatorView&) = delete;
  OperatorView& operator=(const OperatorView&) = delete;

  // Binds params.listen (port 0: any free port) and starts serving; false with an error naming
  // the address.
  bool start(std::string& error);
  // Ends every stream, stops the server and joins its threads. Idempotent.
  void stop();

  int port() const { return port_; }
  std::string url() const;
  // One line for the command that serves the view to print once started: whether the address is
  // reachable beyond this machine (then it begins "warning: ") and whether ABORT and START are
  // enabled.
  std::string exposure() const;
  std::uint64_t frames_encoded() const { return frames_encoded_.load(); }
  std::uint64_t commands_refused() const { return refused_.load(); }
  // Commands with the right token that were not carried out: too old, client gone, or no tick
  // took them in time.
  std::uint64_t commands_dropped() const { return dropped_.load(); }
  int streams_open() const;
  std::uint64_t streams_refused() const;

 private:
  void pump();
  bool authorised(const std::string& token) const;
  void routes();

  OperatorViewParams params_;
  const hal::StereoRig& rig_;
  const hal::MarkerModel& marker_;
  OperatorLink& link_;
  OperatorViewOptions options_;
  std::unique_ptr<ViewHttpServer> server_;
  std::thread server_thread_;
  std::thread pump_thread_;
  std::string host_;
  int port_ = 0;
  bool running_ = false;

  // The latest state and picture, built by the pump thread, read by every client's thread.
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool stopping_ = false;
  std::uint64_t state_seq_ = 0;
  std::uint64_t frame_seq_ = 0;
  std::shared_ptr<const std::string> state_json_;
  std::shared_ptr<const std::string> jpeg_;
  std::atomic<std::uint64_t> abort_tick_{0};

  std::atomic<std::uint64_t> frames_encoded_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace rovctl::app
