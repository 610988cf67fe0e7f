// `rovctl faults` on a small subset, through the real binary: each injected fault is detected as
// its cause, made safe within 2 ticks and logged; a transient one recovers; unknown names exit 2.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <string>

namespace {

struct CliRun {
  int code = -1;
  std::string out;
};

CliRun rovctl(const std::string& args) {
  const std::string command = std::string(ROVCTL_BINARY) + " " + args + " 2>/dev/null";
  CliRun r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) r.out += buffer.data();
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The JSON row of `fault` (the writer emits one object per fault, fields in a fixed order).
std::string row(const std::string& json, const std::string& fault) {
  const auto at = json.find("\"fault\": \"" + fault + "\"");
  if (at == std::string::npos) return "";
  return json.substr(at, json.find('}', at) - at);
}

TEST(CommandFaults, SubsetIsDetectedSafeLoggedAndTransientRecovers) {
  const CliRun r = rovctl("faults --json --only sensor_nan,frozen_frames --jobs 2");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string nan = row(r.out, "sensor_nan");
  ASSERT_FALSE(nan.empty()) << r.out;
  EXPECT_NE(nan.find("\"cause\": \"sensor_nan\""), std::string::npos) << nan;
  EXPECT_NE(nan.find("\"detected\": 1"), std::string::npos) << nan;
  EXPECT_NE(nan.find("\"logged\": 1"), std::string::npos) << nan;
  EXPECT_NE(nan.find("\"ticks_to_safe_max\": 1"), std::string::npos) << nan;
  const std::string frozen = row(r.out, "frozen_frames");
  ASSERT_FALSE(frozen.empty()) << r.out;
  EXPECT_NE(frozen.find("\"detected\": 1"), std::string::npos) << frozen;
  EXPECT_NE(frozen.find("\"recovered\": 1"), std::string::npos) << frozen;
  EXPECT_NE(frozen.find("\"docked\": 1"), std::string::npos) << frozen;
  EXPECT_EQ(r.out.find("camera_lost"), std::string::npos) << "only the subset runs";
}

TEST(CommandFaults, UnknownFaultIsAUsageError) {
  EXPECT_EQ(rovctl("faults --only meteor").code, 2);
  EXPECT_EQ(rovctl("sim --fault meteor@3").code, 2);
  EXPECT_EQ(rovctl("sim --fault camera_lost@soon").code, 2);
}

}  // namespace
