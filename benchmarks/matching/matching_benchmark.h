// benchmark_matching as functions (docs/matching_results.md): the parsing of its list flags and the
// whole markdown report, every figure junction matching must show (issue 4) against ground truth.
// a. Generated sequences (make_sequence, with truth/): consecutive pairs, F from the true poses and
//    from the noisy odometry; a junction takes the visible wireframe vertex nearest to it within the radius.
// b. VGG Corridor imported with simulated odometry: matches under the odometry F, judged with the F
//    of the true projection matrices and, near ground-truth junctions, by their identity.
// c. The paper's Table 2: rho and sigma over tau2 x R on one VGG pair and one generated pair.
// d. OpenCV line_descriptor (LSD + binary LBD) on the same pairs, judged the same way.
// e. Time of MatchJunctions, median of repeats; f. the geometric verification of each pair.
#pragma once

#include <string>
#include <vector>

#include "frontend/junctions/junction_options.h"
#include "frontend/matching/matching_options.h"
#include "frontend/segments/segment_detector.h"
#include "geometry/image_undistorter.h"
#include "util/status.h"

namespace sfm {

// The detector and matcher under test.
struct MatchingBenchmarkSettings {
  UndistortInterpolation undistort_interpolation = kDetectionInterpolation;
  SegmentDetectorOptions segments;
  JunctionDetectorOptions junctions;
  MatchingOptions matching;
};

// What the report measures and how (benchmark_matching's flags of the same names).
struct MatchingBenchmarkOptions {
  std::vector<std::string> generated;  // generated sequence directories (with truth/)
  std::string vgg_sequence;     // the VGG Corridor imported by import_sequence --format vgg; "" leaves it out
  std::string vgg_dir;          // the VGG Corridor data set (bt.NNN.P, bt.NNN.lines, bt_original.nview-lines)
  std::string image_dir;        // Fig. 6-style pictures of the Table 2 pairs there when not empty
  std::string vgg_matches_csv;  // every match of the consecutive VGG pairs with its diagnosis, when not empty
  std::string segments;         // the segment detector's name, for the report's first line
  double radius = 3.0;          // a junction lies at a true vertex / ground-truth junction within this, px
  double epipolar_tolerance = 2.0;  // a correct match lies within this of the true epipolar lines, px
  int max_gap = 2;                  // VGG: pairs up to this many frames apart
  std::vector<double> table2_R{4, 6, 10, 15};  // px
  std::vector<double> table2_tau2{0.05, 0.1, 0.2, 0.3};
  int table2_vgg_pair[2] = {0, 1};
  int table2_generated_pair[2] = {10, 11};
  int speed_repeats = 21;     // timings: median of this many runs
  int speed_junctions = 150;  // e: also time the VGG pairs with only this many strongest junctions
  double lbd_min_length = SegmentDetectorOptions().min_length;  // LSD segments shorter are dropped, px
  bool match_pose = true;  // give the matcher the odometry pose and its uncertainty (else F only)
};

// The non-empty items of a comma-separated list.
std::vector<std::string> SplitCommaList(const std::string& text);
// A comma-separated list of finite numbers, at least one.
bool ParseNumberList(const std::string& text, std::vector<double>* values);
// Two different non-negative frame numbers, "a,b".
bool ParseFramePair(const std::string& text, int* a, int* b);

// The markdown report over the generated sequences and the VGG Corridor of `bench`.
Status MatchingBenchmarkReport(const MatchingBenchmarkOptions& bench,
                               const MatchingBenchmarkSettings& settings, std::string* text);

}  // namespace sfm
