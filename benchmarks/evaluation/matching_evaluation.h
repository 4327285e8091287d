// Measuring junction matches, and the line matches of OpenCV's LSD + LBD for comparison, against
// ground truth: used by benchmark_matching and tests/matching_e2e (docs/matching_results.md).
//
// - Generated sequences: each detected junction takes the visible wireframe vertex nearest to it
//   within a radius; a match is right when both its junctions take the same vertex.
// - VGG Corridor: F from the true projection matrices (bt.NNN.P), ground-truth junctions from the
//   ground-truth segments (JunctionsFromSegments of junction_evaluation.h), and their identity
//   across views from the 3D lines of bt_original.nview-lines.
// - Line matches: a detected segment lies on a true segment; identities are 3D lines.
// Junction detection itself is measured by junction_evaluation.h; nothing here repeats it.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "frontend/junctions/junction.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/segments/line_segment.h"
#include "frontend/segments/segment_detector.h"
#include "util/status.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/wireframe.h"
#include "benchmarks/evaluation/junction_evaluation.h"

namespace sfm {

// ---- Features of one frame ---------------------------------------------------------------------

// Processor time of the calling thread, milliseconds (CLOCK_THREAD_CPUTIME_ID): on a shared
// machine, unlike wall time, it does not count the time other processes take.
double ThreadCpuMs();

// What junction matching needs of one (undistorted) image, and the time it took.
struct FrameFeatures {
  LineSegments segments;
  Junctions junctions;
  TopologyGraph graph;
  double detect_ms = 0;  // segments + junctions + topology graph, ThreadCpuMs
};
FrameFeatures DetectFrameFeatures(const cv::Mat& undistorted_grey, const SegmentDetectorOptions& segment_options,
                                  const JunctionDetectorOptions& junction_options);

// ---- Identities and the verdict on one match ---------------------------------------------------

// For each point, the index of the nearest of `targets` within `radius` (px), or -1. Many points
// may take the same target (a junction detected twice at one vertex is at that vertex twice).
std::vector<int> NearestWithin(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& targets,
                               double radius);
std::vector<Eigen::Vector2d> JunctionLocations(const Junctions& junctions);

// Both points within `tolerance` px of the other's epipolar line under F (x2^T F x1 = 0).
bool EpipolarConsistent(const Eigen::Matrix3d& F, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                        double tolerance);

// Whether two features (junction index_a of image 1, index_b of image 2) are the same scene
// feature: +1 yes, 0 no, -1 unknown (no ground truth for one of them).
using SameFeature = std::function<int(int index_a, int index_b)>;

struct MatchVerdicts {
  int matches = 0;
  int correct = 0;
  int epipolar_wrong = 0;  // farther than the tolerance from the true epipolar geometry
  int identity_wrong = 0;  // consistent with it, but ground truth says two different features
  int identity_known = 0;  // matches that ground truth could identify on both sides
  int epipolar_wrong_same = 0;  // of epipolar_wrong, those ground truth calls the same feature
  int correct_known = 0;        // of identity_known, the correct ones
  int Wrong() const { return matches - correct; }
  void Add(const MatchVerdicts& o);
};

// A match is correct when its two points are within `tolerance` px of each other's epipolar line
// under the true F, and, where `same` knows both features, when they are the same one.
MatchVerdicts JudgeMatches(const std::vector<std::pair<int, int>>& matches, const std::vector<Eigen::Vector2d>& points_a,
                           const std::vector<Eigen::Vector2d>& points_b, const Eigen::Matrix3d& F_true,
                           double tolerance, const SameFeature& same);
std::vector<std::pair<int, int>> MatchPairs(const std::vector<JunctionMatch>& matches);

// Recall against ground truth. truth_a[i]: the true feature detection i of image 1 lies on (-1:
// none), truth_b likewise; true_pairs: the true features of the two images that are one scene
// feature. Such a pair is seen in both when detections lie on it in each image, and matched when
// a match joins two of those detections.
struct FeatureRecall {
  int seen_both = 0, matched = 0;
  void Add(const FeatureRecall& o) { seen_both += o.seen_both, matched += o.matched; }
};
FeatureRecall CountRecall(const std::vector<int>& truth_a, const std::vector<int>& truth_b,
                          const std::vector<std::pair<int, int>>& true_pairs,
                          const std::vector<std::pair<int, int>>& matches);

// ---- Generated sequences: junctions at true vertices -------------------------------------------

// For each junction, the wireframe indices of the visible vertices within `radius` of it, nearest
// first (empty: none). Two vertices can project within a few pixels of each other (a poster
// corner 5 mm in front of a cabinet corner, far door frames), and a junction there is at both.
std::vector<std::vector<int>> TrueVerticesNearJunctions(const Junctions& junctions, const FrameTruth& frame,
                                                        double radius);

// +1 when the two lists share a vertex, 0 when they do not, -1 when either is empty.
int SameTrueVertex(const std::vector<int>& near_a, const std::vector<int>& near_b);

// Why a vertex seen in both frames was not matched (first reason that applies), from rho (34) of
// its two junctions nearest the vertex.
enum class MissReason {
  kSegmentCount,   // the two junctions have different numbers of segments: never candidates
  kEpipolar,       // d or d' > R (or the pair's pose band)
  kCheirality,     // triangulates behind a camera (PairGeometry given, use_cheirality)
  kNoShift,        // no segment correspondence passes (17), (36) and (37): rho = 0
  kRule,           // rho > 0, lost in rule (38): another candidate better, or not by tau2
  kNumReasons
};
const char* MissReasonName(MissReason reason);

struct VertexMatchCounts {
  int pairs = 0;
  int matches = 0;
  int associated = 0;     // matches whose two junctions are both within the radius of a true vertex
  int same_vertex = 0;    // of those, within the radius of one same vertex
  int same_nearest = 0;   // of those, with the same nearest vertex (stricter where vertices crowd)
  int seen_both = 0;      // vertices with a junction within the radius in each frame
  int seen_both_same_count = 0;  // of those, with junctions of equal segment count in the two frames
  int matched = 0;        // of seen_both, joined by a match between junctions within the radius of it
  // Of seen_both_same_count, joined by a full match (junctions of equal segment counts): the recall
  // of the paper's rule, at most seen_both_same_count.
  int matched_same_count = 0;
  // Of matched, joined by partial matches only (junctions of k and k + 1 segments; docs/matching.md,
  // "Partial correspondence"): matched = matched by a full match + matched_partial_only.
  int matched_partial_only = 0;
  int misses[static_cast<int>(MissReason::kNumReasons)] = {};
  void Add(const VertexMatchCounts& o);
};

// Scores the matches of one pair of generated frames; near_a, near_b from TrueVerticesNearJunctions.
// F (or geometry, when not null: F = geometry->Fundamental()) and options are those the matches
// were made with (for the reasons of misses).
VertexMatchCounts ScoreVertexMatches(const Junctions& a, const Junctions& b, const std::vector<std::vector<int>>& near_a,
                                     const std::vector<std::vector<int>>& near_b, const std::vector<JunctionMatch>& matches,
                                     const Eigen::Matrix3d& F, const MatchingOptions& options,
                                     const PairGeometry* geometry = nullptr);

// ---- VGG Corridor ground truth -----------------------------------------------------------------

struct VggView {
  Eigen::Matrix<double, 3, 4> P = Eigen::Matrix<double, 3, 4>::Zero();  // bt.NNN.P, image pixels
  LineSegments lines;               // bt.NNN.lines
  std::vector<int> line3d;          // per line: its row of bt.l3d (bt_original.nview-lines), or -1
  std::vector<SegmentJunction> junctions;          // JunctionsFromSegments(lines)
  std::vector<std::vector<int>> junction_lines3d;  // per junction: distinct 3D lines of its segments, sorted
  std::vector<Eigen::Vector2d> corners;            // bt.NNN.corners (Harris)
  std::vector<int> corner_point3d;                 // per corner: its row of bt.p3d (bt.nview-corners), or -1
};

struct VggTruth {
  std::vector<VggView> views;  // bt.000, bt.001, ... up to the first missing image
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lines3d;  // bt.l3d: end-points (the files' frame)
};

// The image line (a x + b y + c = 0) of the infinite 3D line through X0 and X1 under P.
Eigen::Vector3d ProjectLine(const Eigen::Matrix<double, 3, 4>& P, const Eigen::Vector3d& X0, const Eigen::Vector3d& X1);

// Reads bt.NNN.P, bt.NNN.lines, bt.NNN.corners, bt.l3d, bt_original.nview-lines and
// bt.nview-corners (3D identities of lines and corners; unidentified when the files are absent)
// from the data set directory.
Status ReadVggTruth(const std::string& directory, const SegmentJunctionOptions& junction_options, VggTruth* truth);

// A 3x4 matrix written as 12 numbers (bt.NNN.P).
Status ReadProjectionMatrix(const std::string& path, Eigen::Matrix<double, 3, 4>* P);

// Two ground-truth junctions of two views are one when they share at least two 3D lines; +1, 0,
// or -1 when either has fewer than two identified lines.
int SameVggJunction(const VggView& a, int junction_a, const VggView& b, int junction_b);

// For each point, the 3D points (bt.p3d rows) of the view's reconstructed corners within `radius`
// px, nearest first. Harris corners fire at junctions, so these are the VGG's true vertices.
std::vector<std::vector<int>> VggPointsNear(const VggView& view, const std::vector<Eigen::Vector2d>& points,
                                            double radius);

// ---- Line matches (OpenCV line_descriptor) ------------------------------------------------------

struct LineAssociationOptions {
  double max_distance = 2.0;   // px: both detected end-points this close to the true line
  double max_angle_deg = 3.0;  // degrees
  double min_overlap = 0.5;    // share of the detected length lying over the true segment
};

// For each detected segment, the true segment it lies on (largest overlap), or -1.
std::vector<int> AssociateSegments(const LineSegments& detected, const LineSegments& truth,
                                   const LineAssociationOptions& options);

// The epipolar band of each segment (between the epipolar lines of its end-points) meets the other
// segment, within `tolerance` px, both ways: the only constraint F puts on a line match.
bool SegmentsEpipolarConsistent(const Eigen::Matrix3d& F, const LineSegment& a, const LineSegment& b,
                                double tolerance);

// 3D line identity of each wireframe edge: edges on one 3D line (within 1 mm) share an id.
std::vector<int> WireframeLineIds(const Wireframe& wireframe);

// A generated frame's visible edge parts as segments (undistorted px) and their 3D line ids.
void TrueLinesOfFrame(const FrameTruth& frame, const std::vector<int>& edge_line_id, LineSegments* lines,
                      std::vector<int>* line_ids);

// Both end-points of s within max_distance px of `line` (a x + b y + c = 0) and the directions
// within max_angle_deg. False for a degenerate line.
bool SegmentOnLine(const LineSegment& s, const Eigen::Vector3d& line, const LineAssociationOptions& options);

// The image line of 3D line `id` in one image (a x + b y + c = 0).
using LineOfId = std::function<Eigen::Vector3d(int id)>;

// Line matches judged like junction matches. id_a, id_b: the 3D line each detected segment lies on
// (-1: none known). A match is correct when epipolar-consistent under F_true and, where either
// segment lies on a known 3D line, when the other segment lies on that line's image in its own
// image (SegmentOnLine with the association options): F alone only says the segments overlap.
// Recall: of the 3D lines with a detected segment on them in both images, the share joined by a
// match between such segments.
struct LineMatchScore {
  MatchVerdicts verdicts;
  int seen_both = 0, matched = 0;
  void Add(const LineMatchScore& o);
};
LineMatchScore ScoreLineMatches(const LineSegments& a, const LineSegments& b,
                                const std::vector<std::pair<int, int>>& matches, const std::vector<int>& id_a,
                                const std::vector<int>& id_b, const LineOfId& line_in_a, const LineOfId& line_in_b,
                                const Eigen::Matrix3d& F_true, double tolerance);

// OpenCV's LSD detector (one octave, as the line_descriptor tutorial) and binary LBD descriptors.
struct LbdFeatures {
  LineSegments segments;
  cv::Mat descriptors;  // one row per segment
  double detect_ms = 0;  // LSD + descriptors, ThreadCpuMs (call cv::setNumThreads(1) first)
};
LbdFeatures DetectLbd(const cv::Mat& grey, double min_length);

// BinaryDescriptorMatcher brute force (Hamming): for each line of a its nearest in b; with
// `mutual`, only pairs that are each other's nearest.
std::vector<std::pair<int, int>> MatchLbd(const cv::Mat& descriptors_a, const cv::Mat& descriptors_b, bool mutual);

}  // namespace sfm
