// The matcher's gates centred on pose hypotheses (GuidedPassOrHypotheses) on a facade whose window
// panes repeat: Strecha entry-P10 with three times the importer's default odometry noise.
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>

#include "pipeline/pipeline.h"
#include "sequences/importers/imported_sequence.h"
#include "sequences/importers/strecha_importer.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;

// Figures protected: with the odometry's rotation error moving the epipolar lines by about a pane,
// the odometry-centred gates matched seven of the 17 pairs one pane off and the refined shape was
// worse than the odometry's (Sim(3) ATE 0.319 m against 0.187 m). Centred on the hypotheses, at
// least 4 pairs move (measured 6) and the refined Sim(3) ATE is at most 0.12 m (measured 0.090 m)
// and below the odometry's.
TEST(PoseHypothesesTest, StrechaEntryP10AtThreeTimesTheOdometryNoise) {
  const std::string data = testing::SharedDataDir("strecha-entry-P10");
  if (data.empty()) GTEST_SKIP() << "../shared/data/strecha-entry-P10 is absent";
  const fs::path scratch = testing::MakeScratchDir("pose_hypotheses_entry");
  ImportedSequence imported;
  ASSERT_TRUE(ReadStrechaSequence(data, &imported).ok());
  SequenceWriteOptions write;
  write.odometry = write.odometry.Scaled(3);
  write.seed = 1;
  ASSERT_TRUE(WriteImportedSequence(imported, write, (scratch / "sequence").string()).ok());
  PipelineOptions options;
  options.sequence_dir = (scratch / "sequence").string();
  options.output_dir = (scratch / "output").string();
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
