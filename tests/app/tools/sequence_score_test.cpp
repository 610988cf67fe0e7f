// Scoring rendered sequences frame by frame on the committed sample (one hidden-sphere sequence,
// every 10th frame of 90): every frame counted once per arm, no ok-but-wrong frame in either, the
// tracker carrying the pose where the still estimator's confirmation cannot (a third of a second
// between frames), and a missing file named.
#include "app/tools/sequence_score.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"

namespace rovctl::app {
namespace {

const std::string kSequenceSample = std::string(ROVCTL_TEST_DATA_DIR) + "/water_sequences";

TEST(SequenceScore, TheSampleIsScoredFrameByFrameWithNoOkButWrongFrame) {
  const AppConfig config = load_app_config(default_config_path());
  const hal::StereoRig rig = load_rig(config);
  const std::vector<RenderedSequence> sequences = load_sequences(kSequenceSample);
  ASSERT_EQ(sequences.size(), 1u);
  EXPECT_EQ(sequences[0].kind, "hidden");
  ASSERT_EQ(sequences[0].frames.size(), 9u);
  const SequenceScores scores = score_sequences(rig, config.marker, config.estimator,
                                                config.control.tracker, sequences, 1, 0);
  ASSERT_EQ(scores.frames.size(), 9u);
  ASSERT_FALSE(scores.by_event.empty());
  const SequenceScoreRow& all = scores.by_event.back();
  EXPECT_EQ(all.label, "all");
  for (const ArmCount& arm : {all.still, all.tracked}) {
    EXPECT_EQ(arm.frames, 9);
    EXPECT_EQ(arm.right + arm.wrong + arm.not_ok, arm.frames);
    EXPECT_EQ(arm.wrong, 0);
  }
  // 1/3 s between frames is past the confirmation's gap, so the still arm is never ok; the tracker
  // confirms the estimates against its own prediction.
  EXPECT_EQ(all.still.right, 0);
  EXPECT_GE(all.tracked.right, 4);
  int hidden = 0;
  for (const FrameScore& f : scores.frames) hidden += f.frame->hidden_sphere ? 1 : 0;
  ASSERT_EQ(scores.by_event.front().label, "hidden-sphere frames");
  EXPECT_EQ(scores.by_event.front().tracked.frames, hidden);
  EXPECT_GT(hidden, 0);
}

TEST(SequenceScore, AMissingFileIsNamed) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "rovctl_sequence_score_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "a");
  { std::ofstream(dir / "sequences.json") << R"({"sequences": [{"name": "a", "path": "a"}]})"; }
  try {
    load_sequences(dir.string());
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a/sequence.json: missing"), std::string::npos)
        << e.what();
  }
  try {
    load_sequences((dir / "none").string());
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("none: not a folder"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rovctl::app
