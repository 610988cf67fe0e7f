// The operator view's server against an HTTP client: the page, the state, the picture, the
// streams, BlueOS registration, ABORT/START guarded by the token and carried out at once or
// never, streams bounded, and commands through whatever the viewers hold.
#include "app/view/operator_view.hpp"

#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "control/mission.hpp"

namespace rovctl::app {
namespace {

constexpr const char* kToken = "s3cret-token";

struct Fixture {
  AppConfig config = load_app_config(default_config_path());
  hal::StereoRig rig = load_rig(config);
  OperatorLink link{rig, std::chrono::milliseconds(0)};
  OperatorViewParams params;
  Fixture() {
    params.listen = "127.0.0.1:0";
    params.token = kToken;
    params.frame_rate_hz = 30.0;
  }
  // The view on this fixture's link, started; null (and the test failed) when it did not start.
  std::unique_ptr<OperatorView> start_view() {
    auto view = std::make_unique<OperatorView>(params, rig, config.marker, link);
    std::string error;
    if (view->start(error)) return view;
    ADD_FAILURE() << error;
    return nullptr;
  }
  // One tick in the docking state with an estimate, and a frame of it.
  void publish_tick(std::uint64_t tick) {
    TelemetryRecord r;
    r.tick = tick;
    r.time_s = 0.033 * static_cast<double>(tick);
    r.mission_state = static_cast<std::int32_t>(control::MissionState::approach);
    r.fitness = 0.9;
    r.est_t_m = {0.0, 0.0, 0.6};
    r.est_q_wxyz = {1.0, 0.0, 0.0, 0.0};
    r.thruster_count = 2;
    r.thruster_cmd[0] = 0.25;
    r.thruster_cmd[1] = -0.5;
    r.flags = telemetry_flag::estimate_valid | telemetry_flag::full_view | telemetry_flag::armed;
    hal::StereoFrame frame;
    frame.left_bgr =
        cv::Mat(rig.left.height_px, rig.left.width_px, CV_8UC3, cv::Scalar(40, 30, 20));
    frame.right_bgr =
        cv::Mat(rig.right.height_px, rig.right.width_px, CV_8UC3, cv::Scalar(40, 30, 20));
    link.publish(r, &frame, std::chrono::nanoseconds(static_cast<std::int64_t>(tick) * 33000000));
  }
};

// POST of a command with the operator's token, as the page sends it.
httplib::Result post_command(httplib::Client& client, const char* path) {
  return client.Post(path, httplib::Headers{{"X-Rovctl-Token", kToken}}, "", "text/plain");
}

// Polls until `pred` holds (the pump runs every 50 ms).
template <class Pred>
bool eventually(Pred pred) {
  for (int i = 0; i < 100; ++i) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// A tick on its own thread: publishes and takes commands every 10 ms, counting what it took.
struct Ticker {
  Fixture& f;
  std::atomic<bool> running{true};
  std::atomic<int> aborts{0};
  std::atomic<int> starts{0};
  std::atomic<std::uint64_t> abort_tick{0};
  std::thread thread;
  Ticker(Fixture& fixture, std::uint64_t first) : f(fixture) {
    thread = std::thread([this, first] {
      for (std::uint64_t t = first; running; ++t) {
        if (f.link.take_abort()) {
          ++aborts;
          abort_tick = t;
        }
        if (f.link.take_start()) ++starts;
        f.publish_tick(t);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    });
  }
  void stop() {
    running = false;
    if (thread.joinable()) thread.join();
  }
  ~Ticker() { stop(); }
};

// A bare TCP client: sends what it is told, reads what comes.
struct RawClient {
  int fd = -1;
  explicit RawClient(int port) {
    fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) ADD_FAILURE() << "connect";
  }
  ~RawClient() { close(fd); }
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;
  void send(const std::string& bytes) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return;  // the server closed (it refused what it read)
      sent += static_cast<std::size_t>(n);
    }
  }
  std::string read_until(const std::string& marker, std::chrono::milliseconds timeout) {
    std::string got;
    const auto until = std::chrono::steady_clock::now() + timeout;
    char buf[4096];
    while (got.find(marker) == std::string::npos && std::chrono::steady_clock::now() < until) {
      pollfd p{fd, POLLIN, 0};
      if (poll(&p, 1, 50) <= 0) continue;
      const ssize_t n = recv(fd, buf, sizeof(buf), 0);
      if (n <= 0) break;
      got.append(buf, static_cast<std::size_t>(n));
    }
    return got;
  }
};

TEST(OperatorView, ServesThePageStateAndPicture) {
  Fixture f;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  ASSERT_GT(view->port(), 0);
  httplib::Client client("127.0.0.1", view->port());
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<title>rovctl operator view</title>"), std::string::npos);
  EXPECT_EQ(page->body.find("http://"), std::string::npos) << "nothing fetched from elsewhere";
  EXPECT_EQ(page->body.find("https://"), std::string::npos);

  auto none = client.Get("/state");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 503) << "no tick yet";

  f.publish_tick(7);
  ASSERT_TRUE(eventually([&] {
    auto s = client.Get("/state");
    return s && s->status == 200;
  }));
  auto state = client.Get("/state");
  EXPECT_NE(state->body.find("\"state\": \"approach\""), std::string::npos) << state->body;
  EXPECT_NE(state->body.find("\"tick\": 7"), std::string::npos) << state->body;
  EXPECT_NE(state->body.find("\"thrust_fraction\": [0.25, -0.5]"), std::string::npos)
      << state->body;

  ASSERT_TRUE(eventually([&] {
    auto s = client.Get("/snapshot.jpg");
    return s && s->status == 200;
  }));
  auto jpeg = client.Get("/snapshot.jpg");
  const std::vector<uchar> bytes(jpeg->body.begin(), jpeg->body.end());
  const cv::Mat picture = cv::imdecode(bytes, cv::IMREAD_COLOR);
  ASSERT_FALSE(picture.empty());
  EXPECT_EQ(picture.cols, f.rig.left.width_px + f.rig.right.width_px) << "both cameras";
  EXPECT_EQ(picture.rows, f.rig.left.height_px);
  // The estimate is drawn: the picture is no longer the flat background everywhere.
  cv::Mat diff;
  cv::absdiff(picture, cv::Scalar(40, 30, 20), diff);
  cv::Mat grey;
  cv::cvtColor(diff, grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey > 60), 100) << "sphere outlines on the picture";
  EXPECT_GE(view->frames_encoded(), 1u);
  view->stop();
}

TEST(OperatorView, CommandsNeedTheToken) {
  Fixture f;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  f.publish_tick(41);
  httplib::Client client("127.0.0.1", view->port());
  auto bare = client.Post("/abort");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->status, 403);
  auto wrong =
      client.Post("/abort", httplib::Headers{{"X-Rovctl-Token", "s3cret-tokeN"}}, "", "text/plain");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 403);
  EXPECT_FALSE(f.link.take_abort()) << "a refused ABORT changes nothing";
  EXPECT_EQ(view->commands_refused(), 2u);
  auto get = client.Get("/abort");
  ASSERT_TRUE(get);
  EXPECT_NE(get->status, 200) << "ABORT is POST only";
  EXPECT_FALSE(f.link.take_abort());

  Ticker ticker(f, 42);
  auto ok = post_command(client, "/abort");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200) << ok->body;
  EXPECT_NE(ok->body.find("\"accepted\": \"ABORT\""), std::string::npos) << ok->body;
  auto start = post_command(client, "/start");
  ASSERT_TRUE(start);
  EXPECT_EQ(start->status, 200) << start->body;
  ticker.stop();
  EXPECT_EQ(ticker.aborts, 1) << "one request, one abort";
  EXPECT_EQ(ticker.starts, 1);
  // The answer names the tick that took it.
  EXPECT_NE(ok->body.find("\"tick\": " + std::to_string(ticker.abort_tick)), std::string::npos)
      << ok->body;
  EXPECT_EQ(view->commands_dropped(), 0u);
}

// A command no tick takes within command_max_age_ms is answered 503 and withdrawn: a tick that
// runs afterwards never sees it.
TEST(OperatorView, ACommandNoTickTakesIsDroppedNotAppliedLater) {
  Fixture f;
  f.params.command_max_age_ms = 100.0;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  f.publish_tick(5);
  httplib::Client client("127.0.0.1", view->port());
  auto r = post_command(client, "/start");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503);
  EXPECT_NE(r->body.find("START not applied: no tick took it"), std::string::npos) << r->body;
  EXPECT_EQ(view->commands_dropped(), 1u);
  EXPECT_FALSE(f.link.take_start()) << "withdrawn: the next tick does not take it";
}

// A START that timed out at a busy server's client must not run when the server comes to it.
// Here START B waits behind START A (which no tick takes: the command path is held for
// command_max_age_ms); B's client gives up meanwhile; then the tick runs. B is never applied.
TEST(OperatorView, AStartWhoseClientGaveUpIsNeverApplied) {
  Fixture f;
  f.params.command_max_age_ms = 300.0;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  f.publish_tick(5);
  int a_status = 0;
  std::thread a([&] {
    httplib::Client client("127.0.0.1", view->port());
    auto r = post_command(client, "/start");
    a_status = r ? r->status : -1;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // A holds the command path
  bool b_answered = true;
  {
    httplib::Client client("127.0.0.1", view->port());
    client.set_read_timeout(std::chrono::milliseconds(100));
    auto r = post_command(client, "/start");
    b_answered = static_cast<bool>(r);
  }  // B's client closes its connection: it gave up
  EXPECT_FALSE(b_answered) << "B was still waiting when its client gave up";
  a.join();
  EXPECT_EQ(a_status, 503) << "A: no tick took it within its bound";
  Ticker ticker(f, 6);  // the tick runs from here on, taking whatever START reaches it
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  ticker.stop();
  EXPECT_EQ(ticker.starts, 0) << "neither START ran after its client saw it fail";
  EXPECT_EQ(view->commands_dropped(), 2u);
}

// A request that took longer than command_max_age_ms to arrive (its first byte, then the rest)
// is too old to apply, even with the tick running and the client still waiting.
TEST(OperatorView, ACommandOlderThanItsBoundIsDropped) {
  Fixture f;
  f.params.command_max_age_ms = 100.0;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  Ticker ticker(f, 1);
  RawClient c(view->port());
  const std::string request = std::string("POST /start HTTP/1.1\r\nHost: x\r\nX-Rovctl-Token: ") +
                              kToken + "\r\nContent-Length: 0\r\n\r\n";
  c.send(request.substr(0, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  c.send(request.substr(10));
  const std::string answer = c.read_until("not applied", std::chrono::seconds(2));
  EXPECT_EQ(answer.rfind("HTTP/1.1 503", 0), 0u) << answer;
  EXPECT_NE(answer.find("START not applied: it waited"), std::string::npos) << answer;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ticker.stop();
  EXPECT_EQ(ticker.starts, 0);
}

// Streams are bounded (the next is refused 503 at once), and neither open streams, refused ones,
// idle connections nor half-sent requests stand between ABORT and the tick.
TEST(OperatorView, CommandsGetThroughWhateverTheViewersHold) {
  Fixture f;
  f.params.max_streams = 4;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  Ticker ticker(f, 1);
  std::vector<std::unique_ptr<RawClient>> held;
  for (int i = 0; i < 4; ++i) {  // admitted streams whose clients never read
    held.push_back(std::make_unique<RawClient>(view->port()));
    held.back()->send(i % 2 ? "GET /events HTTP/1.1\r\nHost: x\r\n\r\n"
                            : "GET /stream.mjpg HTTP/1.1\r\nHost: x\r\n\r\n");
  }
  ASSERT_TRUE(eventually([&] { return view->streams_open() == 4; }));
  RawClient fifth(view->port());
  fifth.send("GET /%65vents HTTP/1.1\r\nHost: x\r\n\r\n");  // encoded: still a stream
  const std::string refused = fifth.read_until("\r\n\r\n", std::chrono::seconds(2));
  EXPECT_EQ(refused.rfind("HTTP/1.1 503", 0), 0u) << refused;
  EXPECT_EQ(view->streams_refused(), 1u);
  for (int i = 0; i < 200; ++i) {  // idle connections, and requests that never finish
    held.push_back(std::make_unique<RawClient>(view->port()));
    if (i % 2) held.back()->send("GET /state HTTP/1.1\r\nHost: x\r\nX-Slow: ");
  }
  httplib::Client client("127.0.0.1", view->port());
  client.set_read_timeout(std::chrono::seconds(2));
  auto abort = post_command(client, "/abort");
  ASSERT_TRUE(abort) << "ABORT answered while every stream is taken";
  EXPECT_EQ(abort->status, 200) << abort->body;
  EXPECT_TRUE(eventually([&] {
    auto state = client.Get("/state");
    return state && state->status == 200;
  })) << "pages too";
  ticker.stop();
  EXPECT_EQ(ticker.aborts, 1);
  held.clear();
  // An events stream learns its client left at its next write: the keep-alive, within 1 s.
  EXPECT_TRUE(eventually([&] { return view->streams_open() == 0; }) ||
              eventually([&] { return view->streams_open() == 0; }))
      << "closed streams end";
}

// What a safety probe from outside must keep finding.
TEST(OperatorView, RefusesWhatItDoesNotServe) {
  Fixture f;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  f.publish_tick(3);
  httplib::Client client("127.0.0.1", view->port());
  for (const char* path : {"/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2fetc"}) {
    auto r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
  }
  auto options = client.Options("/abort");
  ASSERT_TRUE(options);
  EXPECT_EQ(options->status, 404);
  for (const auto& r : {client.Get("/"), client.Get("/state"), client.Options("/abort")}) {
    ASSERT_TRUE(r);
    for (const auto& [name, value] : r->headers) {
      EXPECT_EQ(name.rfind("Access-Control-", 0), std::string::npos) << name << ": " << value;
    }
  }
  RawClient big(view->port());
  big.send("GET /state HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(1 << 20, 'a') + "\r\n\r\n");
  const std::string answer = big.read_until("\r\n\r\n", std::chrono::seconds(5));
  EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << answer.substr(0, 80);
  // Two requests in one write on one kept-alive connection: both answered, in order.
  RawClient pipelined(view->port());
  pipelined.send("GET /info HTTP/1.1\r\nHost: x\r\n\r\nGET /nothing HTTP/1.1\r\nHost: x\r\n\r\n");
  const std::string both = pipelined.read_until("404", std::chrono::seconds(2));
  EXPECT_EQ(both.rfind("HTTP/1.1 200", 0), 0u) << both;
  EXPECT_NE(both.find("HTTP/1.1 404"), std::string::npos) << both;
}

TEST(OperatorView, SaysWhatItExposes) {
  Fixture f;
  OperatorView local(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(local.start(error)) << error;
  EXPECT_EQ(local.exposure().find("warning"), std::string::npos) << local.exposure();
  EXPECT_NE(local.exposure().find("commands enabled"), std::string::npos) << local.exposure();
  f.params.listen = "0.0.0.0:0";
  f.params.token.clear();
  OperatorView wide(f.params, f.rig, f.config.marker, f.link);
  ASSERT_TRUE(wide.start(error)) << error;
  EXPECT_EQ(wide.exposure().rfind("warning: the operator view listens on every address", 0), 0u)
      << wide.exposure();
  EXPECT_NE(wide.exposure().find("read-only"), std::string::npos) << wide.exposure();
}

TEST(OperatorView, WithoutATokenTheViewIsReadOnly) {
  Fixture f;
  f.params.token.clear();
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  httplib::Client client("127.0.0.1", view->port());
  auto r = client.Post("/abort", httplib::Headers{{"X-Rovctl-Token", ""}}, "", "text/plain");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_NE(r->body.find("read-only"), std::string::npos);
  EXPECT_FALSE(f.link.take_abort());
}

TEST(OperatorView, StreamsEventsAndPictures) {
  Fixture f;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  std::atomic<bool> publishing{true};
  std::thread ticks([&] {
    for (std::uint64_t t = 1; publishing; ++t) {
      f.publish_tick(t);
      std::this_thread::sleep_for(std::chrono::milliseconds(33));
    }
  });
  httplib::Client client("127.0.0.1", view->port());
  std::string events;
  client.Get("/events", [&](const char* data, std::size_t n) {
    events.append(data, n);
    return events.find("data: ", events.find("data: ") + 1) == std::string::npos;  // two events
  });
  std::string mjpeg;
  client.Get("/stream.mjpg", [&](const char* data, std::size_t n) {
    mjpeg.append(data, n);
    return mjpeg.size() < 40000;
  });
  publishing = false;
  ticks.join();
  EXPECT_EQ(events.rfind("data: {", 0), 0u) << events.substr(0, 80);
  EXPECT_NE(events.find("\n\ndata: {"), std::string::npos) << "a second event follows";
  EXPECT_EQ(mjpeg.rfind("--rovctlframe\r\nContent-Type: image/jpeg\r\n", 0), 0u);
  EXPECT_NE(mjpeg.find("\xff\xd8"), std::string::npos) << "a JPEG start marker";
  view->stop();
  EXPECT_TRUE(eventually([&] { return view->streams_open() == 0; }));
}

TEST(OperatorView, RegistersAsABlueOsService) {
  Fixture f;
  const std::unique_ptr<OperatorView> view = f.start_view();
  ASSERT_NE(view, nullptr);
  httplib::Client client("127.0.0.1", view->port());
  auto r = client.Get("/register_service");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  for (const char* key : {"\"name\"", "\"description\"", "\"icon\"", "\"company\"", "\"version\"",
                          "\"webpage\": \"/\"", "\"api\""}) {
    EXPECT_NE(r->body.find(key), std::string::npos) << key << " in " << r->body;
  }
}

TEST(OperatorView, ABusyAddressIsAClearError) {
  Fixture f;
  OperatorView first(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(first.start(error)) << error;
  OperatorViewParams taken = f.params;
  taken.listen = "127.0.0.1:" + std::to_string(first.port());
  OperatorView second(taken, f.rig, f.config.marker, f.link);
  EXPECT_FALSE(second.start(error));
  EXPECT_NE(error.find(taken.listen), std::string::npos) << error;
}

}  // namespace
}  // namespace rovctl::app
