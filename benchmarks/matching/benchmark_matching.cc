// benchmark_matching: every figure junction matching must show (issue 4), measured against ground
// truth in one run, single thread (docs/matching_results.md; scripts/benchmark_matching.sh
// prepares the sequences and runs it).
//
//   build/bin/benchmark_matching --generated <seq>,<seq> --vgg_sequence <imported seq>
//                                [--vgg_dir ../shared/data/vgg-corridor] --output report.md [flags]
//
// a. Generated sequences (make_sequence, with truth/): consecutive pairs, F from the true poses and
//    from the noisy odometry. Each junction takes the visible wireframe vertex nearest to it within
//    --radius; precision = matches pairing the same vertex among those whose junctions both take
//    one; recall = vertices taken in both frames that a match joins.
// b. VGG Corridor imported with simulated odometry (import_sequence --format vgg): matches under
//    the odometry F, judged with the F of the true projection matrices (--epipolar_tolerance both
//    ways) and, where both junctions lie within --radius of ground-truth junctions identified by
//    their 3D lines, by that identity.
// c. The paper's Table 2: rho and sigma over tau2 x R on one VGG pair and one generated pair.
// d. OpenCV line_descriptor (LSD + binary LBD, brute-force Hamming matching) on the same pairs,
//    judged against the same ground truth, and the time of both methods per pair.
// e. Time of MatchJunctions on the VGG pairs (about 150 junctions per frame), median of repeats.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "benchmarks/matching/matching_benchmark.h"
#include "frontend/matching/matching_options.h"
#include "frontend/segments/segment_detector.h"
#include "sfm_app/flags/detector_flags.h"
#include "util/atomic_file.h"

namespace {
const sfm::MatchingOptions kMatchingDefaults;
}  // namespace

DEFINE_string(generated, "", "Comma-separated generated sequence directories (with truth/), e.g. a corridor and a room.");
DEFINE_string(vgg_sequence, "", "VGG Corridor imported by import_sequence --format vgg (odometry and images).");
DEFINE_string(vgg_dir, "../shared/data/vgg-corridor", "The VGG Corridor data set (bt.NNN.P, bt.NNN.lines, bt_original.nview-lines).");
DEFINE_string(output, "", "Also write the markdown report here.");
DEFINE_string(image_dir, "", "If set, write Fig. 6-style pictures of the Table 2 pairs there (wrong matches' numbers in red).");
DEFINE_double(radius, 3.0, "A junction lies at a true vertex / ground-truth junction within this, px.");
DEFINE_double(epipolar_tolerance, 2.0, "A correct match lies within this of the true epipolar lines, both ways, px.");
DEFINE_int32(max_gap, 2, "VGG: also measure pairs up to this many frames apart (1: consecutive only).");
DEFINE_string(table2_vgg_pair, "0,1", "VGG frames of the Table 2 sweep.");
DEFINE_string(table2_generated_pair, "10,11", "Frames of the first generated sequence for the Table 2 sweep.");
DEFINE_string(table2_tau2, "0.05,0.1,0.2,0.3", "tau2 values of the Table 2 sweep.");
DEFINE_string(table2_R, "4,6,10,15", "R values of the Table 2 sweep, px.");
DEFINE_int32(speed_repeats, 21, "Time each pair's matching this many times and take the median.");
DEFINE_int32(speed_junctions, 150, "e: also time the VGG pairs with only this many strongest junctions per frame.");
DEFINE_double(lbd_min_length, sfm::SegmentDetectorOptions().min_length, "LSD segments shorter than this are dropped, px.");
// The detector and matching flags shared with the other apps (--segments, --endpoint_lambda,
// --match_tau1, ...): sfm_app/flags/detector_flags.h. Those below are this benchmark's own.
DEFINE_bool(match_pose, true,
            "Give the matcher the odometry pose and its uncertainty (sequence.yaml's noise model): per-pair band and "
            "cheirality; false: F only, fixed R.");
DEFINE_double(match_location_sigma, kMatchingDefaults.location_sigma_px, "Junction location sigma, px (band, cheirality).");
DEFINE_int32(match_depth_range_neighbours, kMatchingDefaults.depth_range_neighbours,
             "With --match_refine: the local depth range test's neighbours (0: off).");
DEFINE_string(
    vgg_matches_csv, "",
    "If set, write every match of the consecutive VGG pairs (odometry) with its diagnosis there: verdict, "
    "junction types, distances from the true and the refined epipolar lines, the guided band, rho and "
    "sigma.");

int main(int argc, char** argv) {
  using namespace sfm;
  gflags::SetUsageMessage(
      "junction matching against ground truth, Table 2, LSD + LBD, speed (docs/matching_results.md).\n"
      "  benchmark_matching --generated <seq>,<seq> --vgg_sequence <imported vgg> --output report.md");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  cv::setNumThreads(1);
  auto fail = [](int code, const std::string& message) {
    std::fprintf(stderr, "benchmark_matching: %s\n", message.c_str());
    return code;
  };

  // Flags.
  if (argc > 1) return fail(2, std::string("unexpected argument '") + argv[1] + "' (flags are --name=value)");
  const std::vector<std::string> generated_dirs = SplitCommaList(FLAGS_generated);
  if (generated_dirs.empty() && FLAGS_vgg_sequence.empty()) {
    return fail(2, "give --generated and/or --vgg_sequence (scripts/benchmark_matching.sh prepares both)");
  }
  MatchingBenchmarkSettings settings;
  std::string error;
  if (!SegmentMethodFromFlags(&settings.segments, &error)) return fail(2, error);
  if (!UndistortInterpolationFromFlags(&settings.undistort_interpolation, &error)) return fail(2, error);
  MatchingOptions& matching = settings.matching;
  if (!MatchingFromFlags(&settings.junctions, &matching, &error)) return fail(2, error);
  MatchingRefineFromFlags(&matching);
  matching.location_sigma_px = FLAGS_match_location_sigma;
  matching.depth_range_neighbours = FLAGS_match_depth_range_neighbours;
  for (const Status& check : {settings.segments.Check(), settings.junctions.Check(), matching.Check()}) {
    if (!check.ok()) return fail(2, check.message());
  }
  MatchingBenchmarkOptions bench;
  if (!ParseNumberList(FLAGS_table2_R, &bench.table2_R)) return fail(2, "--table2_R must list numbers, e.g. 4,6,10,15");
  if (!ParseNumberList(FLAGS_table2_tau2, &bench.table2_tau2)) return fail(2, "--table2_tau2 must list numbers");
  if (!ParseFramePair(FLAGS_table2_vgg_pair, &bench.table2_vgg_pair[0], &bench.table2_vgg_pair[1])) return fail(2, "--table2_vgg_pair must be two frames, e.g. 0,1");
  if (!ParseFramePair(FLAGS_table2_generated_pair, &bench.table2_generated_pair[0],
                      &bench.table2_generated_pair[1])) {
    return fail(2, "--table2_generated_pair must be two frames, e.g. 10,11");
  }
  if (FLAGS_radius <= 0 || FLAGS_epipolar_tolerance <= 0 || FLAGS_speed_repeats < 1 || FLAGS_max_gap < 1 ||
      FLAGS_speed_junctions < 1) {
    return fail(2, "--radius and --epipolar_tolerance must be > 0, --speed_repeats, --speed_junctions and --max_gap >= 1");
  }
  if (!FLAGS_image_dir.empty()) {
    if (const Status s = EnsureWritableDirectory(FLAGS_image_dir); !s.ok()) return fail(1, s.message());
  }

  bench.generated = generated_dirs;
  bench.vgg_sequence = FLAGS_vgg_sequence;
  bench.vgg_dir = FLAGS_vgg_dir;
  bench.image_dir = FLAGS_image_dir;
  bench.vgg_matches_csv = FLAGS_vgg_matches_csv;
  bench.segments = FLAGS_segments;
  bench.radius = FLAGS_radius;
  bench.epipolar_tolerance = FLAGS_epipolar_tolerance;
  bench.max_gap = FLAGS_max_gap;
  bench.speed_repeats = FLAGS_speed_repeats;
  bench.speed_junctions = FLAGS_speed_junctions;
  bench.lbd_min_length = FLAGS_lbd_min_length;
  bench.match_pose = FLAGS_match_pose;
  std::string text;
  if (const Status s = MatchingBenchmarkReport(bench, settings, &text); !s.ok()) return fail(1, s.message());
  std::fputs(text.c_str(), stdout);
  if (!FLAGS_output.empty()) {
    if (const Status s = WriteFileAtomically(FLAGS_output, text); !s.ok()) return fail(1, s.message());
  }
  return 0;
}

