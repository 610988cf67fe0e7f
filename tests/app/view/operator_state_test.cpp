// The operator state's JSON: what the page shows of one tick, the not-ok reason by name.
#include "app/view/operator_state.hpp"

#include <gtest/gtest.h>

#include <string>

#include "estimator/pose_estimator.hpp"

namespace rovctl::app {
namespace {

TelemetryRecord recognised_tick(bool ok, estimator::NotOkReason reason) {
  TelemetryRecord r;
  r.tick = 90;
  r.fitness = 0.82;
  r.spheres_seen_left = 3;
  r.spheres_seen_right = 3;
  r.error_bound_m = 0.0137;
  r.error_bound_deg = 3.4;
  r.est_t_m = {0.0, 0.0, 1.4};
  r.est_q_wxyz = {1.0, 0.0, 0.0, 0.0};
  r.not_ok_reason = static_cast<std::int32_t>(reason);
  r.flags = telemetry_flag::estimate_valid | telemetry_flag::recognised;
  if (ok) r.flags |= telemetry_flag::full_view;
  return r;
}

bool has(const std::string& json, const std::string& text) {
  return json.find(text) != std::string::npos;
}

// Every sphere seen and the bound over the line: the page must not call that a partial view.
TEST(OperatorState, SaysWhichTestANotOkEstimateFailed) {
  const std::string bound =
      operator_state_json(recognised_tick(false, estimator::NotOkReason::bound_over_limit), {});
  EXPECT_TRUE(has(bound, "\"ok\": false")) << bound;
  EXPECT_TRUE(has(bound, "\"not_ok_reason\": \"bound_over_limit\"")) << bound;
  EXPECT_TRUE(has(bound, "\"spheres_seen\": [3, 3]")) << bound;
  EXPECT_TRUE(has(bound, "\"error_bound_mm\": 13.7")) << bound;
  EXPECT_TRUE(has(bound, "\"error_bound_deg\": 3.4")) << bound;

  const std::string partial =
      operator_state_json(recognised_tick(false, estimator::NotOkReason::partial_view), {});
  EXPECT_TRUE(has(partial, "\"not_ok_reason\": \"partial_view\"")) << partial;

  const std::string ok =
      operator_state_json(recognised_tick(true, estimator::NotOkReason::none), {});
  EXPECT_TRUE(has(ok, "\"ok\": true")) << ok;
  EXPECT_TRUE(has(ok, "\"not_ok_reason\": \"none\"")) << ok;
}

}  // namespace
}  // namespace rovctl::app
