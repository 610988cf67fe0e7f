// After SIGKILL the controller must not stay armed: `rovctl run` against the pymodbus thruster
// controller is killed with -9, then the ExecStopPost line of deploy/rovctl.service is run as
// systemd would (its paths pointed at this build and this test's config); the controller's log
// must show neutral and armed = 0 within 1 s of the kill, and nothing armed by the step.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "modbus_peer.hpp"
#include "test_tools.hpp"

extern char** environ;

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

double monotonic_s() {  // the controller logs time.monotonic(): CLOCK_MONOTONIC
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

pid_t spawn(const std::vector<std::string>& args, const std::string& out = "") {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!out.empty()) {
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  }
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

int wait_exit(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

using Peer = test::ModbusPeer;

// The mock camera and world with the thrusters on the peer.
std::string write_config(const Peer& peer) {
  const std::string path = peer.dir() + "/vehicle.yaml";
  std::ofstream out(path);
  out << "calibration: " << ROVCTL_SOURCE_DIR << "/deploy/config/stereo_calibration.yaml\n"
      << "thruster_bus:\n  backend: modbus\n  modbus:\n    transport: tcp\n    host: 127.0.0.1\n"
      << "    port: " << peer.port() << "\n    slave_id: 7\n"
      << "control:\n  thruster_health:\n    enabled: false\n";
  return path;
}

struct Write {
  double t = 0.0;
  int address = -1;
  std::vector<int> values;
};

std::vector<Write> read_log(const std::string& path) {
  std::vector<Write> writes;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    Write w;
    std::string kind;
    if (!(ls >> w.t >> kind >> w.address) || kind != "hr") continue;
    int v = 0;
    while (ls >> v) w.values.push_back(v);
    writes.push_back(w);
  }
  return writes;
}

// The unit's ExecStopPost, split as systemd splits it (no shell), with the installed binary and
// config replaced by this build's and this test's.
std::vector<std::string> exec_stop_post(const std::string& config) {
  std::ifstream unit(std::string(ROVCTL_SOURCE_DIR) + "/deploy/rovctl.service");
  std::string line;
  std::vector<std::string> args;
  while (std::getline(unit, line)) {
    const std::string key = "ExecStopPost=";
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream words(line.substr(key.size()));
    std::string w;
    while (words >> w) {
      if (w == "/usr/bin/rovctl") w = ROVCTL_BINARY;
      if (w == "/etc/rovctl/vehicle.yaml") w = config;
      args.push_back(w);
    }
  }
  return args;
}

TEST(ThrustersSafe, ExecStopPostDisarmsTheControllerAfterSigkill) {
  ROVCTL_REQUIRE_TOOL(test::have_pymodbus(), "/usr/bin/python3 has no usable pymodbus");
  Peer peer;
  ASSERT_TRUE(peer.start()) << "pymodbus peer did not start";
  const std::string config = write_config(peer);
  const std::vector<std::string> stop_post = exec_stop_post(config);
  ASSERT_GE(stop_post.size(), 2u) << "deploy/rovctl.service has no ExecStopPost";
  ASSERT_EQ(stop_post[0], ROVCTL_BINARY);

  const pid_t run = spawn({ROVCTL_BINARY, "run", "--config", config, "--quiet", "--telemetry",
                           peer.dir() + "/telemetry.csv"},
                          peer.dir() + "/run.out");
  ASSERT_GT(run, 0);
  // Armed and thrusting: armed = 1 and a non-zero command at the controller.
  const auto end = std::chrono::steady_clock::now() + 20s;
  bool thrusting = false;
  while (!thrusting && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(50ms);
    bool armed = false;
    for (const Write& w : read_log(peer.log())) {
      if (w.address == 17) armed = w.values.at(0) == 1;
      if (armed && w.address == 0) {
        for (int v : w.values) thrusting = thrusting || v != 0;
      }
    }
  }
  ASSERT_TRUE(thrusting) << "rovctl run never armed and thrusted on the peer";
  ::kill(run, SIGKILL);
  const double killed_s = monotonic_s();
  EXPECT_EQ(wait_exit(run), 128 + SIGKILL);

  // What SIGKILL leaves: armed = 1 (the step below is what clears it).
  std::this_thread::sleep_for(50ms);
  int armed_after_kill = -1;
  for (const Write& w : read_log(peer.log())) {
    if (w.address == 17) armed_after_kill = w.values.at(0);
  }
  EXPECT_EQ(armed_after_kill, 1);

  const pid_t post = spawn(stop_post, peer.dir() + "/post.out");
  ASSERT_GT(post, 0);
  const int post_code = wait_exit(post);
  std::string post_out;
  {
    std::ifstream in(peer.dir() + "/post.out");
    std::getline(in, post_out, '\0');
  }
  EXPECT_EQ(post_code, 0) << post_out;

  double neutral_s = -1.0, disarmed_s = -1.0;
  bool armed_again = false;
  for (const Write& w : read_log(peer.log())) {
    if (w.t < killed_s) continue;
    if (w.address == 0 && w.values == std::vector<int>(8, 0) && neutral_s < 0) neutral_s = w.t;
    if (w.address == 17 && w.values.at(0) == 0 && disarmed_s < 0) disarmed_s = w.t;
    armed_again = armed_again || (w.address == 17 && w.values.at(0) != 0);
  }
  ASSERT_GT(neutral_s, 0.0) << "no neutral command after the kill";
  ASSERT_GT(disarmed_s, 0.0) << "no disarm after the kill";
  EXPECT_FALSE(armed_again);
  EXPECT_LT(neutral_s - killed_s, 1.0);
  EXPECT_LT(disarmed_s - killed_s, 1.0);
  std::printf(
      "safe figures: after SIGKILL neutral at +%.1f ms, disarmed at +%.1f ms (the step started "
      "50 ms after the kill)\n",
      (neutral_s - killed_s) * 1e3, (disarmed_s - killed_s) * 1e3);
}

TEST(ThrustersSafe, ExitsOneWhenTheControllerDoesNotAnswer) {
  ROVCTL_REQUIRE_TOOL(test::have_pymodbus(), "/usr/bin/python3 has no usable pymodbus");
  Peer peer;
  ASSERT_TRUE(peer.start()) << "pymodbus peer did not start";
  const std::string config = write_config(peer);
  ::kill(peer.pid(), SIGSTOP);  // hung: connects, never answers
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t post =
      spawn({ROVCTL_BINARY, "thrusters", "--config", config, "--safe", "--timeout-ms", "300"},
            peer.dir() + "/post.out");
  const int code = wait_exit(post);
  const auto took = std::chrono::steady_clock::now() - t0;
  ::kill(peer.pid(), SIGCONT);
  std::string out;
  {
    std::ifstream in(peer.dir() + "/post.out");
    std::getline(in, out, '\0');
  }
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("not acknowledged"), std::string::npos) << out;
  EXPECT_LT(took, 5s);
}

TEST(ThrustersSafe, TestAndSafeTogetherIsAUsageError) {
  const pid_t p =
      spawn({ROVCTL_BINARY, "thrusters", "--config", "/nonexistent.yaml", "--safe", "--test"},
            "/dev/null");
  EXPECT_EQ(wait_exit(p), 2);
}

}  // namespace
}  // namespace rovctl::app
