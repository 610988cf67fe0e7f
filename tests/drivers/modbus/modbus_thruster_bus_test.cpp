// Modbus thruster bus against an independent implementation: pymodbus (python3-pymodbus) plays
// the thruster controller (tests/drivers/modbus/modbus_thruster_controller.py) on loopback TCP and,
// for RTU, on a pseudo-terminal pair made by socat. The controller logs every register write.
#include "drivers/modbus/modbus_thruster_bus.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "test_tools.hpp"

extern char** environ;

namespace rovctl::drivers {
namespace {

namespace fs = std::filesystem;

const char* kPython = "/usr/bin/python3";
const std::string kController =
    std::string(ROVCTL_TEST_DATA_DIR) + "/../drivers/modbus/modbus_thruster_controller.py";

pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  return pid;
}

void stop(pid_t& pid) {
  if (pid <= 0) return;
  ::kill(pid, SIGTERM);
  ::waitpid(pid, nullptr, 0);
  pid = -1;
}

template <class Pred>
bool wait_for(Pred pred, std::chrono::milliseconds limit = std::chrono::seconds(15)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return pred();
}

struct Write {
  int address;
  std::vector<int> values;  // as int16
};

hal::ThrusterCommand command_of(std::vector<double> f) {
  hal::ThrusterCommand c;
  for (std::size_t i = 0; i < f.size(); ++i) c.thrust_fraction[i] = f[i];
  c.count = f.size();
  return c;
}

class ModbusBusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ROVCTL_REQUIRE_TOOL(test::have_pymodbus(), "/usr/bin/python3 has no usable pymodbus");
    char tmpl[] = "/tmp/rovctl_modbus_XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    params_.response_timeout_ms =
        500;  // generous: the machine is shared, this is not a timing test
    params_.retries = 1;
    params_.max_consecutive_failures = 3;
    params_.slave_id = 7;
  }
  void TearDown() override {
    stop(server_);
    stop(socat_);
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  void start_tcp_controller() {
    server_ = spawn({kPython, kController, "--transport", "tcp", "--slave-id", "7", "--log",
                     log_path(), "--ready-file", dir_ + "/ready"});
    ASSERT_GT(server_, 0);
    ASSERT_TRUE(wait_for([&] { return fs::exists(dir_ + "/ready"); })) << "controller not ready";
    std::ifstream ready(dir_ + "/ready");
    std::string word;
    ready >> word >> params_.port;
    params_.transport = "tcp";
    params_.host = "127.0.0.1";
  }

  void start_pty_pair() {
    ROVCTL_REQUIRE_TOOL(test::have_socat(), "socat is not installed");
    socat_ = spawn({"/usr/bin/socat", "pty,raw,echo=0,link=" + dir_ + "/rovctl",
                    "pty,raw,echo=0,link=" + dir_ + "/controller"});
    ASSERT_GT(socat_, 0);
    ASSERT_TRUE(wait_for([&] {
      return fs::exists(dir_ + "/rovctl") && fs::exists(dir_ + "/controller");
    })) << "socat made no pty pair";
    params_.transport = "rtu";
    params_.serial_device = dir_ + "/rovctl";
    params_.baud = 115200;
  }

  void start_rtu_controller() {
    server_ = spawn({kPython, kController, "--transport", "rtu", "--device", dir_ + "/controller",
                     "--slave-id", "7", "--log", log_path(), "--ready-file", dir_ + "/ready"});
    ASSERT_GT(server_, 0);
    ASSERT_TRUE(wait_for([&] { return fs::exists(dir_ + "/ready"); })) << "controller not ready";
  }

  std::string log_path() const { return dir_ + "/writes.log"; }

  std::vector<Write> writes() const {
    std::vector<Write> out;
    std::ifstream in(log_path());
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream s(line);
      double t = 0;
      std::string kind;
      Write w;
      if (!(s >> t >> kind) || kind != "hr" || !(s >> w.address)) continue;
      int v = 0;
      while (s >> v) w.values.push_back(v >= 32768 ? v - 65536 : v);
      out.push_back(w);
    }
    return out;
  }

  bool log_contains(const std::string& word) const {
    std::ifstream in(log_path());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text.find(word) != std::string::npos;
  }

  // Commands and heartbeats in arrival order, checked against what the bus was asked.
  void exercise_bus() {
    ModbusThrusterBus bus(params_, 8);
    std::string error;
    ASSERT_TRUE(bus.open(error)) << error;
    const hal::ThrusterCommand cmd = command_of({0.5, -0.25, 1.5, NAN, -1.0, 0.0004, 0.0, -0.9996});
    EXPECT_EQ(bus.write(cmd), hal::BusStatus::ok);  // disarmed: neutral
    EXPECT_EQ(bus.arm(true), hal::BusStatus::ok);
    EXPECT_EQ(bus.write(cmd), hal::BusStatus::ok);
    EXPECT_EQ(bus.write(cmd), hal::BusStatus::ok);
    hal::ThrusterTelemetry t;
    EXPECT_EQ(bus.read(t), hal::BusStatus::ok);
    EXPECT_TRUE(t.valid);
    ASSERT_EQ(t.count, 8U);
    EXPECT_DOUBLE_EQ(t.speed_rpm[0], 1500.0);  // the stand-in answers 3 rpm per permille
    EXPECT_DOUBLE_EQ(t.speed_rpm[1], -750.0);
    EXPECT_EQ(t.fault_flags[0], 0x100);
    EXPECT_EQ(t.fault_flags[7], 0x107);
    EXPECT_EQ(bus.arm(false), hal::BusStatus::ok);
    bus.close();
    bus.close();

    const std::vector<int> neutral(8, 0);
    const std::vector<int> driven{500, -250, 1000, 0, -1000, 0, 0, -1000};
    const std::vector<Write> w = writes();
    std::vector<std::string> seq;
    for (const Write& x : w) {
      if (x.address == 0 && x.values == neutral)
        seq.push_back("neutral");
      else if (x.address == 0 && x.values == driven)
        seq.push_back("driven");
      else if (x.address == 0)
        seq.push_back("other commands");
      else if (x.address == 16)
        seq.push_back("hb" + std::to_string(x.values.at(0)));
      else if (x.address == 17)
        seq.push_back("armed" + std::to_string(x.values.at(0)));
      else
        seq.push_back("register " + std::to_string(x.address));
    }
    EXPECT_EQ(seq, (std::vector<std::string>{"neutral", "armed0",  // open
                                             "hb1", "neutral",     // disarmed write
                                             "neutral", "armed1",  // arm
                                             // the heartbeat first: thrust only to a peer
                                             // that has just answered
                                             "hb2", "driven", "hb3", "driven", "neutral",
                                             "armed0",                // disarm
                                             "neutral", "armed0"}));  // close
    EXPECT_EQ(bus.counters().errors, 0U);
  }

  std::string dir_;
  pid_t server_ = -1;
  pid_t socat_ = -1;
  ModbusParams params_;
};

TEST(ModbusPermille, Conversion) {
  EXPECT_EQ(thrust_permille(0.5), 500);
  EXPECT_EQ(thrust_permille(-1.2), -1000);
  EXPECT_EQ(thrust_permille(std::nan("")), 0);
  EXPECT_EQ(thrust_permille(0.0015), 2);
}

TEST_F(ModbusBusTest, TcpCommandsHeartbeatAndTelemetry) {
  start_tcp_controller();
  if (HasFatalFailure() || IsSkipped()) return;
  exercise_bus();
}

TEST_F(ModbusBusTest, RtuCommandsHeartbeatAndTelemetry) {
  start_pty_pair();
  if (HasFatalFailure() || IsSkipped()) return;
  start_rtu_controller();
  if (HasFatalFailure() || IsSkipped()) return;
  exercise_bus();
}

TEST_F(ModbusBusTest, TcpSilentSlaveFailsOpenNamingIt) {
  start_tcp_controller();
  if (HasFatalFailure() || IsSkipped()) return;
  params_.slave_id = 9;  // the controller only answers unit 7
  params_.response_timeout_ms = 50;
  ModbusThrusterBus bus(params_, 8);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("127.0.0.1:" + std::to_string(params_.port)), std::string::npos) << error;
  EXPECT_NE(error.find("slave 9"), std::string::npos) << error;
  EXPECT_NE(error.find("does not answer"), std::string::npos) << error;
  EXPECT_EQ(bus.write(command_of({0.3})), hal::BusStatus::fault);
}

TEST_F(ModbusBusTest, TcpNobodyListening) {
  start_tcp_controller();
  if (HasFatalFailure() || IsSkipped()) return;
  stop(server_);  // the port was free a moment ago; now nobody listens there
  ModbusThrusterBus bus(params_, 8);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("cannot connect"), std::string::npos) << error;
}

TEST_F(ModbusBusTest, RtuSilentLineFailsOpen) {
  start_pty_pair();  // nobody on the other end
  if (HasFatalFailure() || IsSkipped()) return;
  params_.response_timeout_ms = 50;
  ModbusThrusterBus bus(params_, 8);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find(params_.serial_device), std::string::npos) << error;
  EXPECT_NE(error.find("does not answer"), std::string::npos) << error;
}

TEST(ModbusBusOpen, MissingSerialPortIsNamed) {
  ModbusParams p;
  p.transport = "rtu";
  p.serial_device = "/dev/rovctl-no-such-tty";
  ModbusThrusterBus bus(p, 8);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("/dev/rovctl-no-such-tty"), std::string::npos) << error;
  EXPECT_NE(error.find("cannot open the serial port"), std::string::npos) << error;
}

TEST_F(ModbusBusTest, ControllerLostDuringRunFaultsAfterNTicks) {
  start_tcp_controller();
  if (HasFatalFailure() || IsSkipped()) return;
  params_.response_timeout_ms = 100;
  ModbusThrusterBus bus(params_, 8);
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  const hal::ThrusterCommand cmd = command_of({0.2, 0.2});
  ASSERT_EQ(bus.write(cmd), hal::BusStatus::ok);
  stop(server_);
  EXPECT_EQ(bus.write(cmd), hal::BusStatus::degraded);
  EXPECT_EQ(bus.write(cmd), hal::BusStatus::degraded);
  EXPECT_EQ(bus.write(cmd), hal::BusStatus::fault);
  EXPECT_EQ(bus.counters().consecutive_failures, 3);
  EXPECT_GE(bus.counters().errors, 6U);  // 3 ticks x (1 + 1 retry)
  EXPECT_FALSE(bus.counters().last_error.empty());
}

// The heartbeat contract: when rovctl stops ticking (it died), the controller stops.
TEST_F(ModbusBusTest, StalledHeartbeatStopsTheController) {
  start_tcp_controller();
  if (HasFatalFailure() || IsSkipped()) return;
  ModbusThrusterBus bus(params_, 8);
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  ASSERT_EQ(bus.write(command_of({0.3, 0.3})), hal::BusStatus::ok);
  EXPECT_TRUE(wait_for([&] { return log_contains("watchdog_stop"); }));
}

}  // namespace
}  // namespace rovctl::drivers
