// Issue 21: a 150 degree equidistant lens finds the junctions a pinhole lens finds in the same
// room. Both sequences from the generator (room, loop, seed 1, 20 frames); detection as the
// pipeline runs it (ImageUndistorter's full view: the fisheye's perspective sub-views); recall as
// benchmark_junctions --truth_in_image=false --truth_in_stored_pixels reads it: detectable
// vertices (two visible edges of at least 10 stored px) seen 3 px inside the stored image, found
// within 3 stored px (docs/junction_results.md, "Wide lenses").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/evaluation/junction_evaluation.h"
#include "frontend/junctions/topology.h"
#include "frontend/junctions/undistorted_junctions.h"
#include "frontend/sequence/sequence.h"
#include "geometry/image_undistorter.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/sequence_writer.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

struct Recall {
  int detectable = 0, found = 0, outer_detectable = 0, outer_found = 0;  // outer: beyond 47 deg off axis
  int cross_view_links = 0;  // topology edges between junctions kept by two different sub-views
  double Percent() const { return 100.0 * found / detectable; }
};

Recall MeasureRecall(bool fisheye) {
  GeneratorOptions generator;
  generator.scene.type = SceneType::kRoom;
  generator.trajectory.type = TrajectoryType::kLoop;
  generator.trajectory.num_frames = 20;
  generator.seed = 1;
  generator.png_compression = 1;
  if (fisheye) {
    generator.camera.model = DistortionModel::kEquidistant;
    generator.camera.fx = generator.camera.fy =
        generator.camera.EquidistantFocalForDiagonal(150 * M_PI / 180);
  }
  const std::string dir =
      testing::MakeScratchDir(fisheye ? "fisheye_recall_fisheye" : "fisheye_recall_pinhole");
  EXPECT_TRUE(GenerateSequence(generator, dir, /*overwrite=*/true).ok());
  Sequence sequence;
  GroundTruth truth;
  EXPECT_TRUE(ReadSequence(dir, &sequence).ok());
  EXPECT_TRUE(ReadGroundTruth(dir, &truth).ok());
  const Camera& camera = sequence.calibration.camera;
  const ImageUndistorter undistorter(camera, kDetectionInterpolation, kDetectionView);
  EXPECT_EQ(!undistorter.SubViews().empty(), fisheye);
  TrueJunctionOptions truth_options;
  truth_options.stored_camera = &camera;
  const double radius = 3;
  Recall recall;
  for (int f = 0; f < static_cast<int>(sequence.frames.size()); ++f) {
    cv::Mat image;
    EXPECT_TRUE(LoadFrameImage(sequence, f, &image).ok());
    std::vector<Eigen::Vector2d> detectable, detected;
    for (const TrueVertexJunction& v :
         TrueJunctionsOfFrame(truth.wireframe, truth.frames[f], truth_options).vertices) {
      if (v.detectable && SeenByStoredImage(camera, v.location, radius)) {
        detectable.push_back(camera.DistortPixel(v.location));
      }
    }
    const Junctions junctions =
        DetectUndistortedJunctions(undistorter, image, SegmentDetectorOptions(), JunctionDetectorOptions());
    for (const Junction& j : junctions) detected.push_back(camera.DistortPixel(j.location));
    if (fisheye) {
      auto view_of = [&](const Junction& j) {
        return undistorter.SubViewOf(
            Eigen::Vector3d((j.location.x() - camera.cx) / camera.fx, (j.location.y() - camera.cy) / camera.fy, 1)
                .normalized());
      };
      for (const TopologyEdge& edge : BuildTopologyGraph(junctions).edges) {
        recall.cross_view_links += view_of(junctions[edge.junction_a]) != view_of(junctions[edge.junction_b]);
      }
    }
    std::vector<bool> found(detectable.size(), false);
    for (const PointMatch& match : MatchPoints(detectable, detected, radius)) found[match.truth] = true;
    for (size_t i = 0; i < detectable.size(); ++i) {
      // Equidistant (k = 0): the stored radius is f theta.
      const bool outer = fisheye && std::hypot(detectable[i].x() - camera.cx, detectable[i].y() - camera.cy) >
                                        camera.fx * 47 * M_PI / 180;
      ++recall.detectable;
      recall.found += found[i];
      recall.outer_detectable += outer;
      recall.outer_found += outer && found[i];
    }
  }
  std::printf(
      "[ figures  ] %s room, 20 frames: %d of %d detectable vertices found (%.1f %%); beyond 47 deg: %d of "
      "%d; topology edges across sub-views %d\n",
      fisheye ? "fisheye" : "pinhole", recall.found, recall.detectable, recall.Percent(), recall.outer_found,
      recall.outer_detectable, recall.cross_view_links);
  return recall;
}

// Figures protected: the fisheye's recall at most 5 points below the pinhole's (issue 21; measured
// when written: pinhole 91.3 % of 1152, fisheye 93.8 % of 1412), and beyond 47 degrees off the axis
// at least 88 % (measured 94.7 % of 243). Detection on one full-view canvas instead of the
// sub-views gave 87.5 % and 79.4 %: the second check fails on it. And a line two sub-views see
// is one line of the topology graph: at least 300 edges join junctions of different sub-views
// (measured 526; without the merge of their segments, 0).
TEST(FisheyeRecallTest, EquidistantRoomFindsJunctionsWithinFivePointsOfThePinhole) {
  const Recall pinhole = MeasureRecall(false);
  const Recall fisheye = MeasureRecall(true);
  ASSERT_GT(pinhole.detectable, 500);
  ASSERT_GT(fisheye.outer_detectable, 200);
  EXPECT_GE(fisheye.Percent(), pinhole.Percent() - 5);
  EXPECT_GE(100.0 * fisheye.outer_found / fisheye.outer_detectable, 88);
  EXPECT_GE(fisheye.cross_view_links, 300);
}

}  // namespace
}  // namespace sfm
