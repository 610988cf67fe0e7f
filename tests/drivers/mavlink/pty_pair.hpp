// A pseudo-terminal for serial-link tests (the machine has no serial ArduSub): the code under test
// opens the follower by its path, the test plays the far end on the leader (raw, non-blocking).
#pragma once

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <string>

namespace rovctl::drivers::testing {

struct PtyPair {
  int leader = -1;
  int follower = -1;
  std::string path;  // the follower's, e.g. /dev/pts/3
  PtyPair() {
    std::array<char, 128> name{};
    if (::openpty(&leader, &follower, name.data(), nullptr, nullptr) != 0) return;
    path = name.data();
    termios t{};
    ::tcgetattr(leader, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(leader, TCSANOW, &t);
    ::fcntl(leader, F_SETFL, ::fcntl(leader, F_GETFL) | O_NONBLOCK);
  }
  ~PtyPair() {
    if (leader >= 0) ::close(leader);
    if (follower >= 0) ::close(follower);
  }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;
  bool ok() const { return leader >= 0; }
};

}  // namespace rovctl::drivers::testing
