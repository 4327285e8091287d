// The matcher's gates centred on pose hypotheses (GuidedPassOrHypotheses) on a facade whose window
// panes repeat: Strecha entry-P10 with three times the importer's default odometry noise.
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>

#include "pipeline/pipeline.h"
#include "tests/keypoints/strecha_entry.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;

// Figures protected: with the odometry's rotation error moving the epipolar lines by about a pane,
// the odometry-centred gates matched seven of the 17 pairs one pane off and the refined shape was
// worse than the odometry's (Sim(3) ATE 0.319 m against 0.187 m). Centred on the hypotheses, at
// least 4 pairs move (measured 6) and the refined Sim(3) ATE is at most 0.12 m (measured 0.058 m)
// and below the odometry's.
TEST(PoseHypothesesTest, StrechaEntryP10AtThreeTimesTheOdometryNoise) {
  const std::string sequence = testing::ImportStrechaEntryAtThreeTimesTheNoise("pose_hypotheses_entry");
  if (sequence.empty()) GTEST_SKIP() << "../shared/data/strecha-entry-P10 is absent";
  PipelineOptions options;
  options.sequence_dir = sequence;
  options.output_dir = (fs::path(sequence).parent_path() / "output").string();
  options.show_progress = false;
  PipelineResult result;
  const Status status = RunPipeline(options, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_TRUE(result.drift_odometry && result.drift_refined);
  std::cout << "[ figure   ] pairs recentred " << result.initialization.recentred_pairs << ", Sim(3) ATE refined "
            << result.drift_refined->ate_sim3_m << " m, odometry " << result.drift_odometry->ate_sim3_m << " m\n";
  EXPECT_GE(result.initialization.recentred_pairs, 4);
  EXPECT_LE(result.drift_refined->ate_sim3_m, 0.12);
  EXPECT_LT(result.drift_refined->ate_sim3_m, result.drift_odometry->ate_sim3_m);
}

}  // namespace
}  // namespace sfm
