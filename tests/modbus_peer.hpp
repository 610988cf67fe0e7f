// The independent Modbus thruster controller the bus tests fly against: pymodbus
// (tests/drivers/modbus/modbus_thruster_controller.py) on loopback TCP as slave 7, logging every
// register write to its folder. One process per ModbusPeer, stopped (and its folder removed) with
// it.
#pragma once

#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace rovctl::test {

class ModbusPeer {
 public:
  ModbusPeer() = default;
  ModbusPeer(const ModbusPeer&) = delete;
  ModbusPeer& operator=(const ModbusPeer&) = delete;
  ~ModbusPeer() {
    if (pid_ > 0) {
      ::kill(pid_, SIGCONT);  // a test may have left it stopped
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }

  // Starts the peer answering every request `delay_ms` late (plus the script's `extra` options);
  // false when it has not said it is ready within 15 s.
  bool start(int delay_ms = 0, const std::vector<std::string>& extra = {}) {
    char tmpl[] = "/tmp/rovctl_modbus_peer_XXXXXX";
    if (::mkdtemp(tmpl) == nullptr) return false;
    dir_ = tmpl;
    std::vector<std::string> args = {
        "/usr/bin/python3",
        std::string(ROVCTL_SOURCE_DIR) + "/tests/drivers/modbus/modbus_thruster_controller.py",
        "--transport",
        "tcp",
        "--slave-id",
        "7",
        "--log",
        log(),
        "--ready-file",
        dir_ + "/ready",
        "--delay-ms",
        std::to_string(delay_ms)};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return false;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(15);
    while (!std::filesystem::exists(dir_ + "/ready")) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the port is written after
    std::ifstream ready(dir_ + "/ready");
    std::string word;
    ready >> word >> port_;
    return port_ > 0;
  }

  pid_t pid() const { return pid_; }
  int port() const { return port_; }
  const std::string& dir() const { return dir_; }
  std::string log() const { return dir_ + "/log"; }

 private:
  pid_t pid_ = -1;
  std::string dir_;
  int port_ = 0;
};

}  // namespace rovctl::test
