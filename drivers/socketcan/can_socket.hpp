// A non-blocking file descriptor carrying struct can_frame: a raw SocketCAN socket bound to an
// interface, or an adopted descriptor (e.g. a socketpair in tests). Error frames are counted.
#pragma once

#include <cstdint>
#include <string>

#include "drivers/socketcan/dronecan_codec.hpp"

namespace rovctl::drivers {

struct CanErrorCounters {
  std::uint64_t error_frames = 0;     // every error frame the controller reported
  std::uint64_t bus_off_events = 0;   // CAN_ERR_BUSOFF
  std::uint64_t restarts = 0;         // CAN_ERR_RESTARTED (controller back from bus-off)
  std::uint64_t error_passive = 0;    // CAN_ERR_CRTL with rx/tx error-passive
  std::uint64_t no_ack = 0;           // CAN_ERR_ACK: nobody acknowledged our frame
  std::uint64_t send_errors = 0;      // send() failures other than a full queue
  std::uint64_t send_queue_full = 0;  // ENOBUFS/EAGAIN: frame dropped
  std::uint64_t receive_errors = 0;
  std::uint64_t ignored_frames = 0;  // standard-ID, RTR or malformed frames
};

class CanSocket {
 public:
  enum class Io { ok, would_block, error };

  CanSocket() = default;
  ~CanSocket();
  CanSocket(CanSocket&& other) noexcept;
  CanSocket& operator=(CanSocket&& other) noexcept;
  CanSocket(const CanSocket&) = delete;
  CanSocket& operator=(const CanSocket&) = delete;

  // Raw CAN socket on `interface` with error frames enabled; false and a message naming the
  // interface when the kernel has no SocketCAN, the interface is missing or down.
  bool open(const std::string& interface, std::string& error);
  // Takes ownership of `fd` (made non-blocking); `label` names it in messages.
  void adopt(int fd, const std::string& label);
  void close();
  bool is_open() const { return fd_ >= 0; }
  const std::string& label() const { return label_; }

  // Sends one extended-ID data frame without blocking.
  Io send(const dronecan::CanFrame& frame);
  // The next extended-ID data frame, if any; error frames are counted (and update bus_off())
  // and skipped.
  Io receive(dronecan::CanFrame& frame);

  bool bus_off() const { return bus_off_; }
  int last_errno() const { return last_errno_; }
  const CanErrorCounters& counters() const { return counters_; }

 private:
  int fd_ = -1;
  std::string label_;
  bool bus_off_ = false;
  int last_errno_ = 0;
  CanErrorCounters counters_;
};

}  // namespace rovctl::drivers
