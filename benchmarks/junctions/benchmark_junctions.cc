// benchmark_junctions: quality of junction detection and the end-point model of eq. (5), measured
// against ground truth in one run (docs/junction_results.md, docs/endpoint_model.md).
//
//   build/bin/benchmark_junctions --output junction_results.md [--work_dir /tmp/junction_benchmark]
//                                 [--sequences a,b] [--segments fast,reference] [junction flags]
//
// Run from the repository's top directory (the default --vgg_dir is relative to it). Single thread.
// 1. Generated sequences: unless --sequences names existing ones, three are generated into
//    --work_dir with the generator library (fixed seeds, so the same bytes every run): a corridor
//    (straight), a room (loop) and a corridor with barrel distortion (turns). Each frame is
//    undistorted with ImageUndistorter, segments and junctions detected, and the junctions
//    compared with the true vertices of the frame (junction_evaluation.h).
// 2. VGG Corridor: ground-truth junctions built from the ground-truth segments (bt.NNN.lines)
//    whose ends meet; recall and precision of the detected junctions against them.
// 3. End-point model: t offsets of detected segments against the true edge parts (generated) and
//    the ground-truth segments (VGG), and the maximum-likelihood lambda and mu (FitEndpointModel).
// Markdown tables go to stdout and to --output. The measurements: junction_benchmark.h.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/evaluation/junction_evaluation.h"
#include "benchmarks/junctions/junction_benchmark.h"
#include "frontend/segments/segment_detector.h"
#include "sequences/generator/renderer.h"
#include "sfm_app/flags/detector_flags.h"
#include "util/atomic_file.h"

namespace {
const sfm::TrueJunctionOptions kTruthDefaults;
const sfm::SegmentJunctionOptions kGtDefaults;
const sfm::EndpointOffsetOptions kOffsetDefaults;
}  // namespace

DEFINE_string(output, "", "Also write the markdown report to this file.");
DEFINE_string(work_dir, "/tmp/junction_benchmark", "Where the generated sequences are written (replaced each run).");
DEFINE_string(sequences, "",
              "Comma-separated generated sequence directories (with truth/) to measure instead of generating "
              "the standard three.");
DEFINE_int32(frames, 30, "Frames of each generated sequence.");
DEFINE_string(vgg_dir, "../shared/data/vgg-corridor", "VGG Corridor directory (bt.NNN.pgm, bt.NNN.lines); skipped if absent.");
DEFINE_string(segments, "fast,reference", "Segment detectors to measure, comma-separated: fast, reference.");
DEFINE_double(min_segment_length, sfm::SegmentDetectorOptions().min_length, "Segment detectors: shortest segment kept, px.");
DEFINE_double(edge_contrast_low, sfm::SegmentDetectorOptions().edge_contrast_low, "Segment detectors: low edge contrast, grey levels.");
DEFINE_double(edge_contrast_high, sfm::SegmentDetectorOptions().edge_contrast_high, "Segment detectors: high edge contrast, grey levels.");
DEFINE_double(log10_nfa_max, sfm::SegmentDetectorOptions().fast.log10_nfa_max, "Fast segments: NFA threshold, log10.");
DEFINE_double(presmooth_sigma, sfm::SegmentDetectorOptions().fast.presmooth_sigma,
              "Fast segments: Gaussian pre-smoothing before the Sobel pass, px.");
DEFINE_double(line_tolerance, sfm::SegmentDetectorOptions().fast.line_tolerance, "Fast segments: splitting tolerance, px.");
// The junction flags (--endpoint_lambda, --endpoint_mu, --junction_min_probability, ...) are
// shared with the other apps: sfm_app/flags/detector_flags.h.
DEFINE_string(overlay_dir, "", "If set, write overlays there (every 10th generated frame, every VGG image), "
                               "with missed true junctions circled in white.");
DEFINE_double(noise_sigma, sfm::RenderOptions().noise_sigma,
              "Generated images: sensor noise sigma, grey levels (the generator's; the contrast rule's unit).");
DEFINE_double(min_contrast_sigmas, 3.0,
              "Contrast-visible reading: a true edge counts when its noise-free grey-level step is at least this "
              "many noise sigmas.");
DEFINE_string(miss_dir, "",
              "If set, write there misses.csv (one row per long edge of each missed detectable vertex whose "
              "segments are missing: length, contrast, the closest detection) and a crop of each such vertex "
              "(8x enlarged, true long edges orange), for finding why edges get no segment.");
DEFINE_bool(
    truth_in_image, true,
    "Generated: true vertices count only --radius px inside the undistorted image, and a true edge's "
    "length only inside it (with barrel distortion the stored image sees beyond it); false: only the "
    "stored image's border applies.");
DEFINE_bool(
    truth_in_stored_pixels, false,
    "Generated: --min_edge_px and the main recall's --radius in the stored (distorted) image's pixels, "
    "where the sensor resolves edges; for wide lenses, whose undistorted periphery is stretched many times.");
DEFINE_double(radius, 3.0, "A true junction is found when a detected one lies within this, px.");
DEFINE_double(min_edge_px, kTruthDefaults.min_edge_px,
              "Generated: a vertex is detectable when at least two visible edges at least this long (px) meet there.");
DEFINE_string(gt_contact_px, "3,5",
              "VGG: how close ground-truth segment ends must come to meet, px; a comma-separated list gives one "
              "set of ground-truth junctions each (overlays and end-point fits use the first).");
DEFINE_double(gt_min_angle_deg, kGtDefaults.min_angle_deg, "VGG: ground-truth segments closer to parallel never meet, degrees.");
DEFINE_double(max_abs_t, kOffsetDefaults.max_abs_t, "End-point samples with |t| above this are gross failures, px.");
DEFINE_int32(junction_repeats, 1,
             "The junction time is the fastest of this many runs on the same segments (VGG: also printed per image to stderr).");


int main(int argc, char** argv) {
  using namespace sfm;
  gflags::SetUsageMessage(
      "junction quality and the end-point model against ground truth (docs/junction_results.md).\n"
      "  benchmark_junctions --output report.md [--work_dir dir] [--sequences a,b] [--segments fast,reference]");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  auto fail = [](int code, const std::string& message) {
    std::fprintf(stderr, "benchmark_junctions: %s\n", message.c_str());
    return code;
  };
  if (argc > 1) return fail(2, std::string("unexpected argument '") + argv[1] + "' (flags are --name=value)");

  SegmentDetectorOptions segment_options;
  segment_options.min_length = FLAGS_min_segment_length;
  segment_options.edge_contrast_low = FLAGS_edge_contrast_low;
  segment_options.edge_contrast_high = FLAGS_edge_contrast_high;
  segment_options.fast.log10_nfa_max = FLAGS_log10_nfa_max;
  segment_options.fast.line_tolerance = FLAGS_line_tolerance;
  segment_options.fast.presmooth_sigma = FLAGS_presmooth_sigma;
  std::vector<JunctionBenchmarkMethod> methods;
  if (const Status s = ParseSegmentMethods(FLAGS_segments, segment_options, &methods); !s.ok()) {
    return fail(2, s.message());
  }
  std::vector<double> contacts;
  if (const Status s = ParseContactDistances(FLAGS_gt_contact_px, &contacts); !s.ok()) return fail(2, s.message());
  JunctionDetectorOptions junction_options;
  JunctionDetectorFromFlags(&junction_options);
  if (const Status check = junction_options.Check(); !check.ok()) return fail(2, check.message());
  for (const std::string& directory : {FLAGS_overlay_dir, FLAGS_miss_dir}) {
    if (directory.empty()) continue;
    if (const Status s = EnsureWritableDirectory(directory); !s.ok()) return fail(1, s.message());
  }

  std::vector<JunctionBenchmarkSequence> sequences;
  if (!FLAGS_sequences.empty()) {
    sequences = GivenSequences(SplitList(FLAGS_sequences));
  } else if (const Status s = GenerateStandardSequences(FLAGS_frames, FLAGS_work_dir, &sequences); !s.ok()) {
    return fail(1, s.message());
  }

  JunctionBenchmarkOptions bench;
  bench.radius = FLAGS_radius;
  bench.min_edge_px = FLAGS_min_edge_px;
  bench.min_contrast_sigmas = FLAGS_min_contrast_sigmas;
  bench.noise_sigma = FLAGS_noise_sigma;
  bench.edge_contrast_high = FLAGS_edge_contrast_high;
  bench.min_segment_length = FLAGS_min_segment_length;
  bench.truth_in_image = FLAGS_truth_in_image;
  bench.truth_in_stored_pixels = FLAGS_truth_in_stored_pixels;
  bench.gt_min_angle_deg = FLAGS_gt_min_angle_deg;
  bench.max_abs_t = FLAGS_max_abs_t;
  bench.junction_repeats = FLAGS_junction_repeats;
  bench.vgg_dir = FLAGS_vgg_dir;
  bench.overlay_dir = FLAGS_overlay_dir;
  bench.miss_dir = FLAGS_miss_dir;
  if (std::string error; !UndistortInterpolationFromFlags(&bench.undistort_interpolation, &error)) {
    return fail(2, error);
  }
  bench.undistort_view = UndistortViewFromFlags();
  std::string text;
  if (const Status s = JunctionBenchmarkReport(bench, sequences, methods, contacts, junction_options, &text); !s.ok()) {
    return fail(1, s.message());
  }
  std::fputs(text.c_str(), stdout);
  if (!FLAGS_output.empty()) {
    if (const Status s = WriteFileAtomically(FLAGS_output, text); !s.ok()) return fail(1, s.message());
  }
  return 0;
}
