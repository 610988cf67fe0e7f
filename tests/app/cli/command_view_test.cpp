// `rovctl view --out DIR`: a finished sim run replayed on the operator page — the recorded states
// come back through /state, marked as a replay, and the page takes no commands.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

// A port nobody listens on now (the kernel's choice; released before the view binds it).
int free_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(s, reinterpret_cast<sockaddr*>(&a), sizeof(a));
  socklen_t n = sizeof(a);
  getsockname(s, reinterpret_cast<sockaddr*>(&a), &n);
  close(s);
  return ntohs(a.sin_port);
}

TEST(CommandView, ReplaysAFinishedRunReadOnly) {
  const fs::path out = fs::temp_directory_path() / "rovctl_view_test";
  fs::remove_all(out);
  ASSERT_EQ(command_sim({"--trials", "1", "--seed", "3", "--max-time", "4", "--out", out.string(),
                         "--plots", "0", "--json"}),
            0);
  ASSERT_TRUE(fs::exists(out / "trial_000.csv"));
  const int port = free_port();
  int code = -1;
  std::thread view([&] {
    code = command_view({"--out", out.string(), "--listen", "127.0.0.1:" + std::to_string(port),
                         "--speed", "4", "--linger", "2"});
  });
  httplib::Client client("127.0.0.1", port);
  std::string state;
  for (int i = 0; i < 100 && state.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (auto r = client.Get("/state"); r && r->status == 200) state = r->body;
  }
  auto info = client.Get("/info");
  auto abort = client.Post("/abort", httplib::Headers{{"X-Rovctl-Token", ""}}, "", "text/plain");
  view.join();
  EXPECT_EQ(code, 0);
  EXPECT_NE(state.find("\"source\": \"replay\""), std::string::npos) << state;
  EXPECT_NE(state.find("\"tick\": "), std::string::npos) << state;
  ASSERT_TRUE(info);
  EXPECT_NE(info->body.find("\"images\": false"), std::string::npos) << info->body;
  ASSERT_TRUE(abort);
  EXPECT_EQ(abort->status, 403) << "a replay takes no commands";
  fs::remove_all(out);
}

// Listening beyond loopback is said out loud by every command that serves the view, with
// whether it takes commands.
TEST(CommandView, ListeningOnEveryAddressPrintsTheExposureWarning) {
  const fs::path out = fs::temp_directory_path() / "rovctl_view_exposure";
  fs::remove_all(out);
  ASSERT_EQ(command_sim({"--trials", "1", "--seed", "3", "--max-time", "1", "--out", out.string(),
                         "--plots", "0", "--json"}),
            0);
  testing::internal::CaptureStderr();
  const int code = command_view(
      {"--out", out.string(), "--listen", "0.0.0.0:0", "--speed", "50", "--linger", "0.1"});
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, 0);
  EXPECT_NE(said.find("warning: the operator view listens on every address of this machine"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("read-only: a replay takes no commands"), std::string::npos) << said;
  fs::remove_all(out);
}

TEST(CommandView, AFolderWithoutTrialsIsAUsageError) {
  const fs::path empty = fs::temp_directory_path() / "rovctl_view_empty";
  fs::create_directories(empty);
  EXPECT_THROW(command_view({"--out", empty.string()}), UsageError);
  EXPECT_THROW(command_view({}), UsageError);
}

}  // namespace
}  // namespace rovctl::app
