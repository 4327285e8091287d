// The evaluation code of benchmark_junctions on hand-made inputs: ground-truth junctions from
// segments (VGG rule), one-to-one matching, true junctions of a frame, end-point offsets.
#include "benchmarks/evaluation/junction_evaluation.h"

#include <gtest/gtest.h>

#include <utility>

#include "tests/test_segments.h"

namespace sfm {
namespace {

using testing::Segment;

// ---- JunctionsFromSegments -------------------------------------------------------------------

TEST(JunctionsFromSegmentsTest, EndsMeetingGiveAnLAtTheLineIntersection) {
  // Horizontal and vertical segments whose ends stop 1.5 and 2 px short of (100, 50).
  const LineSegments segments = {Segment(40, 50, 98.5, 50), Segment(100, 120, 100, 52)};
  const std::vector<SegmentJunction> junctions = JunctionsFromSegments(segments, SegmentJunctionOptions());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_NEAR(junctions[0].location.x(), 100, 1e-9);
  EXPECT_NEAR(junctions[0].location.y(), 50, 1e-9);
  EXPECT_EQ(junctions[0].type, JunctionType::kL);
  EXPECT_EQ(junctions[0].segments, (std::vector<int>{0, 1}));
}

TEST(JunctionsFromSegmentsTest, AnEndOnAnInteriorGivesAT) {
  // The stem ends 2 px above the bar's interior.
  const LineSegments segments = {Segment(20, 80, 180, 80), Segment(90, 20, 90, 78)};
  const std::vector<SegmentJunction> junctions = JunctionsFromSegments(segments, SegmentJunctionOptions());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_NEAR(junctions[0].location.x(), 90, 1e-9);
  EXPECT_NEAR(junctions[0].location.y(), 80, 1e-9);
  EXPECT_EQ(junctions[0].type, JunctionType::kT);
}

TEST(JunctionsFromSegmentsTest, TheContactDistanceDecides) {
  // Ends 4.5 px from the meeting point: no junction at 3 px, one at 5 px.
  const LineSegments segments = {Segment(40, 50, 95.5, 50), Segment(100, 120, 100, 54.5)};
  SegmentJunctionOptions options;
  EXPECT_TRUE(JunctionsFromSegments(segments, options).empty());
  options.contact_px = 5;
  EXPECT_EQ(JunctionsFromSegments(segments, options).size(), 1u);
}

TEST(JunctionsFromSegmentsTest, CrossingInteriorsAndNearParallelPiecesAreNoJunction) {
  SegmentJunctionOptions options;
  // Two interiors crossing at (100, 100): no end meets.
  EXPECT_TRUE(JunctionsFromSegments({Segment(50, 100, 150, 100), Segment(100, 50, 100, 150)}, options).empty());
  // Two pieces of one line 2 px apart, and a pair 5 degrees apart whose ends touch.
  EXPECT_TRUE(JunctionsFromSegments({Segment(0, 10, 50, 10), Segment(52, 10, 100, 10)}, options).empty());
  EXPECT_TRUE(JunctionsFromSegments({Segment(0, 10, 50, 10), Segment(50, 10, 100, 10 + 50 * std::tan(5 * M_PI / 180))},
                                    options)
                  .empty());
}

TEST(JunctionsFromSegmentsTest, ThreeEndsAtOnePointAreOneJunction) {
  // Spokes at 90, 210 and 330 degrees (a Y), each 1 px short of (200, 200).
  LineSegments segments;
  for (double degrees : {90.0, 210.0, 330.0}) {
    const Eigen::Vector2d d(std::cos(degrees * M_PI / 180), std::sin(degrees * M_PI / 180));
    LineSegment s;
    s.p0 = Eigen::Vector2d(200, 200) + 60 * d;
    s.p1 = Eigen::Vector2d(200, 200) + 1 * d;
    segments.push_back(s);
  }
  const std::vector<SegmentJunction> junctions = JunctionsFromSegments(segments, SegmentJunctionOptions());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].segments, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(junctions[0].type, JunctionType::kY);
  EXPECT_NEAR((junctions[0].location - Eigen::Vector2d(200, 200)).norm(), 0, 1e-9);
}

// ---- MatchPoints -----------------------------------------------------------------------------

TEST(MatchPointsTest, OneToOneClosestFirst) {
  const std::vector<Eigen::Vector2d> truth = {{10, 10}, {12, 10}, {50, 50}};
  const std::vector<Eigen::Vector2d> detected = {{11.6, 10}, {80, 80}};
  const std::vector<PointMatch> matches = MatchPoints(truth, detected, 3.0);
  ASSERT_EQ(matches.size(), 1u);  // both truths are near the one detection: the closer one gets it
  EXPECT_EQ(matches[0].truth, 1);
  EXPECT_EQ(matches[0].detected, 0);
  EXPECT_NEAR(matches[0].distance, 0.4, 1e-12);
  EXPECT_TRUE(MatchPoints(truth, {{10, 13.01}}, 3.0).empty());
}

// ---- TrueJunctionsOfFrame and TrueSegmentsOfFrame --------------------------------------------

// A frame seeing vertices 0..4 of a small wireframe:
//   vertex 0 at (100, 100): edges to 1 (60 px right) and 2 (40 px down)      -> detectable L
//   vertex 3 at (300, 100): edges to 1 (140 px left) and 4 (6 px down)      -> not detectable
//   vertex 1 at (160, 100): edges to 0 (left) and 3 (right), collinear       -> no junction
// plus an edge 5-6 whose t[1] end is hidden by an occluder at (400, 250).
struct SmallFrame {
  Wireframe wireframe;
  FrameTruth frame;
};

SmallFrame MakeSmallFrame() {
  SmallFrame f;
  f.wireframe.vertices.assign(7, Eigen::Vector3d::Zero());
  const int edges[][2] = {{0, 1}, {0, 2}, {1, 3}, {3, 4}, {5, 6}};
  for (const auto& e : edges) {
    WireEdge edge;
    edge.vertex_a = e[0];
    edge.vertex_b = e[1];
    f.wireframe.edges.push_back(edge);
  }
  const Eigen::Vector2d pixel[7] = {{100, 100}, {160, 100}, {100, 140}, {300, 100}, {300, 106}, {400, 200}, {400, 300}};
  for (int v : {0, 1, 2, 3, 4}) {
    VisibleVertex vv;
    vv.vertex = v;
    vv.pixel = vv.pixel_distorted = pixel[v];
    f.frame.vertices.push_back(vv);
  }
  for (int e = 0; e < 4; ++e) {
    VisibleSegment s;
    s.edge = e;
    s.pixel[0] = s.pixel_distorted[0] = pixel[edges[e][0]];
    s.pixel[1] = s.pixel_distorted[1] = pixel[edges[e][1]];
    f.frame.segments.push_back(s);
  }
  VisibleSegment hidden;
  hidden.edge = 4;
  hidden.t[1] = 0.5;
  hidden.pixel[0] = pixel[5];
  hidden.pixel[1] = Eigen::Vector2d(400, 250);
  hidden.pixel_distorted[0] = hidden.pixel[0];
  hidden.pixel_distorted[1] = hidden.pixel[1];
  hidden.end[1] = SegmentEnd::kOcclusion;
  f.frame.segments.push_back(hidden);
  return f;
}

TEST(TrueJunctionsOfFrameTest, DetectableNeedsTwoLongNonCollinearEdges) {
  const SmallFrame f = MakeSmallFrame();
  const FrameTrueJunctions truth = TrueJunctionsOfFrame(f.wireframe, f.frame, TrueJunctionOptions());
  // Vertex 0 (L, both edges long) and vertex 3 (two edges, one 6 px long); vertex 1 is a straight
  // line, vertices 2 and 4 have one edge.
  ASSERT_EQ(truth.vertices.size(), 2u);
  EXPECT_EQ(truth.vertices[0].vertex, 0);
  EXPECT_TRUE(truth.vertices[0].detectable);
  EXPECT_EQ(truth.vertices[0].type, JunctionType::kL);
  EXPECT_EQ(truth.vertices[0].num_long_edges, 2);
  EXPECT_EQ(truth.vertices[1].vertex, 3);
  EXPECT_FALSE(truth.vertices[1].detectable);
  EXPECT_EQ(truth.vertices[1].num_edges, 2);
  EXPECT_EQ(truth.vertices[1].num_long_edges, 1);
  ASSERT_EQ(truth.occlusions.size(), 1u);
  EXPECT_EQ(truth.occlusions[0], Eigen::Vector2d(400, 250));
}

// benchmark_junctions --truth_in_image: with the image size given, an edge counts only
// up to where it leaves the image. Vertex 0 at (100, 100) has edges 60 px right and 40 px down; in a
// 640 x 108 image the downward one keeps 7.5 px (to y = 107.5), under min_edge_px = 10, so vertex
// 0 is no longer detectable; in 640 x 130 it keeps 29.5 px and its far end is at y = 129.5.
TEST(TrueJunctionsOfFrameTest, WithTheImageSizeEdgesCountOnlyInsideTheImage) {
  const SmallFrame f = MakeSmallFrame();
  TrueJunctionOptions options;
  options.image_width = 640;
  options.image_height = 108;
  FrameTrueJunctions truth = TrueJunctionsOfFrame(f.wireframe, f.frame, options);
  ASSERT_GE(truth.vertices.size(), 1u);
  EXPECT_EQ(truth.vertices[0].vertex, 0);
  EXPECT_FALSE(truth.vertices[0].detectable);
  EXPECT_EQ(truth.vertices[0].num_long_edges, 1);
  options.image_height = 130;
  truth = TrueJunctionsOfFrame(f.wireframe, f.frame, options);
  ASSERT_GE(truth.vertices.size(), 1u);
  EXPECT_TRUE(truth.vertices[0].detectable);
  ASSERT_EQ(truth.vertices[0].long_edge_ends.size(), 2u);
  EXPECT_NEAR(truth.vertices[0].long_edge_ends[0].x(), 160, 1e-9);  // inside: unchanged
  EXPECT_NEAR(truth.vertices[0].long_edge_ends[1].y(), 129.5, 1e-9);
}

// benchmark_junctions --truth_in_stored_pixels: min_edge_px in the stored image. Vertex 0 at the
// principal point of an equidistant lens (k = 0: stored radius f atan(r / f)) has edges 60 px
// right and 40 px down in the undistorted image: with f = 20 px they are 25.0 and 22.1 stored px
// (detectable); with f = 5 px, 7.4 and 7.2 stored px, under min_edge_px = 10 (not detectable).
TEST(TrueJunctionsOfFrameTest, WithTheStoredCameraEdgesAreMeasuredInStoredPixels) {
  const SmallFrame f = MakeSmallFrame();
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  camera.cx = camera.cy = 100;
  camera.model = DistortionModel::kEquidistant;
  TrueJunctionOptions options;
  options.stored_camera = &camera;
  for (const auto& [focal, detectable] : {std::pair{20.0, true}, std::pair{5.0, false}}) {
    camera.fx = camera.fy = focal;
    const FrameTrueJunctions truth = TrueJunctionsOfFrame(f.wireframe, f.frame, options);
    ASSERT_GE(truth.vertices.size(), 1u);
    EXPECT_EQ(truth.vertices[0].vertex, 0);
    EXPECT_EQ(truth.vertices[0].detectable, detectable) << "f = " << focal;
  }
}

TEST(EdgeContrastsTest, MeanStepAcrossEachEdgeAndTheContrastReading) {
  const SmallFrame f = MakeSmallFrame();
  // Above y = 100: 80; below it, 120 right of x = 100 and 117 left of it. So the edges along
  // y = 100 step by 40 (and by 37 left of x = 100), the edge along x = 100 below y = 100 by 3.
  cv::Mat image(400, 500, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image.at<uchar>(y, x) = y < 100 ? 80 : (x >= 100 ? 120 : 117);
  }
  // Pixel centres are at integers: the edges lie at 99.5; sampling 2 px off still reads the step.
  EdgeContrastOptions options;
  const std::vector<double> contrast = EdgeContrasts(image, f.frame, options);
  ASSERT_EQ(contrast.size(), f.frame.segments.size());
  EXPECT_NEAR(contrast[0], 40, 0.5);  // (100, 100)-(160, 100)
  EXPECT_NEAR(contrast[1], 3, 0.5);   // (100, 100)-(100, 140)
  EXPECT_NEAR(contrast[2], 40, 0.5);  // (160, 100)-(300, 100)
  EXPECT_EQ(contrast[3], -1);          // (300, 100)-(300, 106): no longer than its two end margins
  EXPECT_NEAR(contrast[4], 0, 0.5);   // (400, 200)-(400, 250): flat
  // Vertex 0 is detectable (two long edges) but not contrast-detectable at 6 grey levels.
  TrueJunctionOptions truth_options;
  truth_options.segment_contrast = &contrast;
  truth_options.min_contrast = 6;
  FrameTrueJunctions truth = TrueJunctionsOfFrame(f.wireframe, f.frame, truth_options);
  ASSERT_EQ(truth.vertices[0].vertex, 0);
  EXPECT_TRUE(truth.vertices[0].detectable);
  EXPECT_FALSE(truth.vertices[0].contrast_detectable);
  truth_options.min_contrast = 2;
  truth = TrueJunctionsOfFrame(f.wireframe, f.frame, truth_options);
  EXPECT_TRUE(truth.vertices[0].contrast_detectable);
  // Without contrasts the reading equals the main one.
  truth = TrueJunctionsOfFrame(f.wireframe, f.frame, TrueJunctionOptions());
  EXPECT_TRUE(truth.vertices[0].contrast_detectable);
  // Too short for a sample: -1.
  VisibleSegment tiny;
  tiny.pixel[0] = Eigen::Vector2d(10, 10);
  tiny.pixel[1] = Eigen::Vector2d(15, 10);
  FrameTruth tiny_frame;
  tiny_frame.segments.push_back(tiny);
  EXPECT_EQ(EdgeContrasts(image, tiny_frame, options)[0], -1);
}

TEST(TrueSegmentsOfFrameTest, AnEdgeEndsWhereNoVisibleEdgeContinuesIt) {
  const SmallFrame f = MakeSmallFrame();
  const std::vector<TrueSegment> segments = TrueSegmentsOfFrame(f.wireframe, f.frame, TrueJunctionOptions());
  ASSERT_EQ(segments.size(), 5u);
  // Edge 0-1 ends at vertex 0 (a corner) but not at vertex 1, where edge 1-3 continues it.
  EXPECT_TRUE(segments[0].real_end[0]);
  EXPECT_FALSE(segments[0].real_end[1]);
  EXPECT_FALSE(segments[2].real_end[0]);
  // The occluded edge: its hidden end is real, its far end (marked kVertex, vertex 5 alone) too.
  EXPECT_TRUE(segments[4].real_end[1]);
  EXPECT_EQ(segments[4].end[1], SegmentEnd::kOcclusion);
}

// ---- CollectEndpointOffsets --------------------------------------------------------------------

TEST(CollectEndpointOffsetsTest, SignAndPieces) {
  const LineSegment truth = Segment(0, 0, 100, 0);
  const bool both[2] = {true, true};
  EndpointOffsetOptions options;
  {
    // 3 px short at p0, 1.5 px long at p1 (eq. 8: t = -3 and +1.5); the off-line detection is ignored.
    EndpointOffsets offsets;
    CollectEndpointOffsets({Segment(101.5, -0.2, 3, 0.3), Segment(-10, 2.5, 120, 2.5)}, truth, both, options, &offsets);
    ASSERT_EQ(offsets.t.size(), 2u);
    EXPECT_NEAR(offsets.t[0], -3, 1e-9);
    EXPECT_NEAR(offsets.t[1], 1.5, 1e-9);
  }
  {
    // Detected in two pieces: each end takes the piece next to it.
    EndpointOffsets offsets;
    CollectEndpointOffsets({Segment(2, 0, 40, 0), Segment(45, 0, 98, 0)}, truth, both, options, &offsets);
    ASSERT_EQ(offsets.t.size(), 2u);
    EXPECT_NEAR(offsets.t[0], -2, 1e-9);
    EXPECT_NEAR(offsets.t[1], -2, 1e-9);
  }
  {
    // Nothing on the line; and a detection running 30 px past the end is a gross failure.
    EndpointOffsets offsets;
    CollectEndpointOffsets({}, truth, both, options, &offsets);
    CollectEndpointOffsets({Segment(1, 0, 130, 0)}, truth, both, options, &offsets);
    EXPECT_EQ(offsets.ends, 4);
    EXPECT_EQ(offsets.unmatched, 2);
    EXPECT_EQ(offsets.gross, 1);
    ASSERT_EQ(offsets.t.size(), 1u);
    EXPECT_NEAR(offsets.t[0], -1, 1e-9);
  }
}

}  // namespace
}  // namespace sfm
