// The operator view's server against an HTTP client: the page, the state, the picture, the
// streams, BlueOS registration, and ABORT/START guarded by the token.
#include "app/view/operator_view.hpp"

#include <gtest/gtest.h>
#include <httplib.h>

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

// Polls until `pred` holds (the pump runs every 50 ms).
template <class Pred>
bool eventually(Pred pred) {
  for (int i = 0; i < 100; ++i) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST(OperatorView, ServesThePageStateAndPicture) {
  Fixture f;
  OperatorView view(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(view.start(error)) << error;
  ASSERT_GT(view.port(), 0);
  httplib::Client client("127.0.0.1", view.port());
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
  EXPECT_GE(view.frames_encoded(), 1u);
  view.stop();
}

TEST(OperatorView, CommandsNeedTheToken) {
  Fixture f;
  OperatorView view(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(view.start(error)) << error;
  f.publish_tick(41);
  httplib::Client client("127.0.0.1", view.port());
  auto bare = client.Post("/abort");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->status, 403);
  auto wrong =
      client.Post("/abort", httplib::Headers{{"X-Rovctl-Token", "s3cret-tokeN"}}, "", "text/plain");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 403);
  EXPECT_FALSE(f.link.take_abort()) << "a refused ABORT changes nothing";
  EXPECT_EQ(view.commands_refused(), 2u);
  auto get = client.Get("/abort");
  ASSERT_TRUE(get);
  EXPECT_NE(get->status, 200) << "ABORT is POST only";
  EXPECT_FALSE(f.link.take_abort());

  auto ok = client.Post("/abort", httplib::Headers{{"X-Rovctl-Token", kToken}}, "", "text/plain");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_NE(ok->body.find("\"tick\": 41"), std::string::npos) << ok->body;
  EXPECT_TRUE(f.link.take_abort());
  EXPECT_FALSE(f.link.take_abort()) << "one request, one abort";
  auto start =
      client.Post("/start", httplib::Headers{{"X-Rovctl-Token", kToken}}, "", "text/plain");
  ASSERT_TRUE(start);
  EXPECT_EQ(start->status, 200);
  EXPECT_TRUE(f.link.take_start());
}

TEST(OperatorView, WithoutATokenTheViewIsReadOnly) {
  Fixture f;
  f.params.token.clear();
  OperatorView view(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(view.start(error)) << error;
  httplib::Client client("127.0.0.1", view.port());
  auto r = client.Post("/abort", httplib::Headers{{"X-Rovctl-Token", ""}}, "", "text/plain");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_NE(r->body.find("read-only"), std::string::npos);
  EXPECT_FALSE(f.link.take_abort());
}

TEST(OperatorView, StreamsEventsAndPictures) {
  Fixture f;
  OperatorView view(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(view.start(error)) << error;
  std::atomic<bool> publishing{true};
  std::thread ticks([&] {
    for (std::uint64_t t = 1; publishing; ++t) {
      f.publish_tick(t);
      std::this_thread::sleep_for(std::chrono::milliseconds(33));
    }
  });
  httplib::Client client("127.0.0.1", view.port());
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
  view.stop();
  EXPECT_TRUE(eventually([&] { return view.streams_open() == 0; }));
}

TEST(OperatorView, RegistersAsABlueOsService) {
  Fixture f;
  OperatorView view(f.params, f.rig, f.config.marker, f.link);
  std::string error;
  ASSERT_TRUE(view.start(error)) << error;
  httplib::Client client("127.0.0.1", view.port());
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
