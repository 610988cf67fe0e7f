// sd_notify(3) for Type=notify services: READY=1, STOPPING=1 and WATCHDOG=1 pings, sent as one
// non-blocking datagram to $NOTIFY_SOCKET so the real-time tick can feed the watchdog.
#pragma once

#include <chrono>
#include <string>

namespace rovctl::app {

class SystemdNotifier {
 public:
  SystemdNotifier();  // reads NOTIFY_SOCKET and WATCHDOG_USEC; inactive when not under systemd
  ~SystemdNotifier();
  SystemdNotifier(const SystemdNotifier&) = delete;
  SystemdNotifier& operator=(const SystemdNotifier&) = delete;

  bool active() const { return fd_ >= 0; }
  // Half the watchdog interval systemd asked for, or zero when there is no watchdog.
  std::chrono::nanoseconds watchdog_ping_interval() const { return ping_interval_; }
  void ready() { send("READY=1"); }
  void stopping() { send("STOPPING=1"); }
  // Pings when at least half the watchdog interval has passed since the last ping.
  void feed_watchdog(std::chrono::nanoseconds now);

 private:
  void send(const char* message);
  int fd_ = -1;
  std::string address_;
  std::chrono::nanoseconds ping_interval_{0};
  std::chrono::nanoseconds last_ping_{0};
};

}  // namespace rovctl::app
