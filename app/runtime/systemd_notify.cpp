// The sd_notify datagram protocol, without libsystemd (it is one sendto on a unix socket).
#include "app/runtime/systemd_notify.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace rovctl::app {

SystemdNotifier::SystemdNotifier() {
  const char* socket_path = std::getenv("NOTIFY_SOCKET");
  if (socket_path == nullptr || socket_path[0] == '\0') return;
  address_ = socket_path;
  if (address_.size() >= sizeof(sockaddr_un::sun_path)) return;
  fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (const char* usec = std::getenv("WATCHDOG_USEC"); usec != nullptr) {
    const long long us = std::atoll(usec);
    if (us > 0) ping_interval_ = std::chrono::microseconds(us / 2);
  }
}

SystemdNotifier::~SystemdNotifier() {
  if (fd_ >= 0) ::close(fd_);
}

void SystemdNotifier::feed_watchdog(std::chrono::nanoseconds now) {
  if (fd_ < 0 || ping_interval_.count() == 0 || now - last_ping_ < ping_interval_) return;
  last_ping_ = now;
  send("WATCHDOG=1");
}

void SystemdNotifier::send(const char* message) {
  if (fd_ < 0) return;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, address_.data(), address_.size());
  if (addr.sun_path[0] == '@') addr.sun_path[0] = '\0';  // abstract namespace
  const socklen_t len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + address_.size());
  // MSG_DONTWAIT: a full socket drops one ping rather than stall the tick.
  (void)::sendto(fd_, message, std::strlen(message), MSG_DONTWAIT | MSG_NOSIGNAL,
                 reinterpret_cast<const sockaddr*>(&addr), len);
}

}  // namespace rovctl::app
