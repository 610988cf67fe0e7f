// The notifier speaks the sd_notify datagram protocol to whatever NOTIFY_SOCKET names.
#include "app/runtime/systemd_notify.hpp"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace rovctl::app {
namespace {

TEST(SystemdNotify, InactiveWithoutSocket) {
  unsetenv("NOTIFY_SOCKET");
  SystemdNotifier n;
  EXPECT_FALSE(n.active());
  n.ready();  // harmless
}

TEST(SystemdNotify, SendsReadyAndRateLimitedWatchdog) {
  const std::string path = "/tmp/rovctl-notify-test-" + std::to_string(getpid());
  const int server = socket(AF_UNIX, SOCK_DGRAM, 0);
  ASSERT_GE(server, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", path.c_str());
  unlink(path.c_str());
  ASSERT_EQ(bind(server, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
  setenv("NOTIFY_SOCKET", path.c_str(), 1);
  setenv("WATCHDOG_USEC", "1000000", 1);
  {
    SystemdNotifier n;
    ASSERT_TRUE(n.active());
    EXPECT_EQ(n.watchdog_ping_interval(), std::chrono::milliseconds(500));
    n.ready();
    n.feed_watchdog(std::chrono::milliseconds(600));  // first ping: due
    n.feed_watchdog(std::chrono::milliseconds(700));  // too soon: dropped
    n.feed_watchdog(std::chrono::milliseconds(1200));
  }
  char buf[64];
  std::string got;
  ssize_t k;
  while ((k = recv(server, buf, sizeof(buf), MSG_DONTWAIT)) > 0) got += std::string(buf, k) + ";";
  EXPECT_EQ(got, "READY=1;WATCHDOG=1;WATCHDOG=1;");
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  close(server);
  unlink(path.c_str());
}

}  // namespace
}  // namespace rovctl::app
