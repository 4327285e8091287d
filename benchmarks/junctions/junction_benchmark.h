// benchmark_junctions as functions (docs/junction_results.md, docs/endpoint_model.md): the
// sequences to measure, the parsing of its list flags, and the whole markdown report.
// 1. Generated sequences: each frame undistorted with ImageUndistorter, segments and junctions
//    detected, and the junctions compared with the true vertices of the frame (junction_evaluation.h).
// 2. VGG Corridor: ground-truth junctions built from the ground-truth segments (bt.NNN.lines)
//    whose ends meet; recall and precision of the detected junctions against them.
// 3. End-point model: t offsets of detected segments against the true edge parts (generated) and
//    the ground-truth segments (VGG), and the maximum-likelihood lambda and mu (FitEndpointModel).
#pragma once

#include <string>
#include <vector>

#include "benchmarks/evaluation/junction_evaluation.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/segments/segment_detector.h"
#include "geometry/image_undistorter.h"
#include "sequences/generator/renderer.h"
#include "util/status.h"

namespace sfm {

// What the report measures and how (benchmark_junctions' flags of the same names).
struct JunctionBenchmarkOptions {
  double radius = 3.0;  // a true junction is found when a detected one lies within this, px
  double min_edge_px = TrueJunctionOptions().min_edge_px;  // generated: a detectable vertex's edges, px
  double min_contrast_sigmas = 3.0;  // contrast-visible reading: a true edge's step, noise sigmas
  double noise_sigma = RenderOptions().noise_sigma;  // the generator's sensor noise, grey levels
  double edge_contrast_high = SegmentDetectorOptions().edge_contrast_high;  // the detectors' high threshold
  double min_segment_length = SegmentDetectorOptions().min_length;  // the detectors', px (report text)
  bool truth_in_image = true;  // generated: truth counts only inside the undistorted image
  // Generated: min_edge_px and the main recall's radius in the stored image's pixels (wide lenses)
  bool truth_in_stored_pixels = false;
  double gt_min_angle_deg = SegmentJunctionOptions().min_angle_deg;  // VGG: segments that never meet
  double max_abs_t = EndpointOffsetOptions().max_abs_t;  // end-point samples beyond: gross failures, px
  int junction_repeats = 1;                              // the junction time is the fastest of this many runs
  UndistortInterpolation undistort_interpolation = kDetectionInterpolation;  // generated frames' undistortion
  UndistortView undistort_view = UndistortView::kSameSize;  // detection's view of the generated frames
  std::string vgg_dir;      // VGG Corridor (bt.NNN.pgm, bt.NNN.lines); left out when absent
  std::string overlay_dir;  // overlays there when not empty
  std::string miss_dir;     // misses.csv, notjoined.csv and crops of missed vertices there when not empty
};

// A segment detector under test: its name in the tables and its options.
struct JunctionBenchmarkMethod {
  std::string name;
  SegmentDetectorOptions options;
};

// A generated sequence to measure: its name in the tables, its directory and its noise-free twin
// (same seeds, render noise 0; empty when there is none).
struct JunctionBenchmarkSequence {
  std::string name, directory, clean;
};

// The non-empty items of a comma-separated list.
std::vector<std::string> SplitList(const std::string& text);

// One method per name of `names` ("fast", "reference"), each `base` with that detector.
Status ParseSegmentMethods(const std::string& names, const SegmentDetectorOptions& base,
                           std::vector<JunctionBenchmarkMethod>* methods);

// The contact distances of a comma-separated list, each in (0, 100) px.
Status ParseContactDistances(const std::string& text, std::vector<double>* contacts);

// The given sequence directories, each with <directory>-noise-free as its twin when that exists.
std::vector<JunctionBenchmarkSequence> GivenSequences(const std::vector<std::string>& directories);

// Generates the three standard sequences of `frames` frames (a corridor, a room, a corridor with barrel
// distortion; fixed seeds) and their noise-free twins into `work_dir`, replacing what is there.
Status GenerateStandardSequences(int frames, const std::string& work_dir,
                                 std::vector<JunctionBenchmarkSequence>* sequences);

// The markdown report: every sequence and the VGG Corridor measured with each method.
Status JunctionBenchmarkReport(const JunctionBenchmarkOptions& bench,
                               const std::vector<JunctionBenchmarkSequence>& sequences,
                               const std::vector<JunctionBenchmarkMethod>& methods,
                               const std::vector<double>& contacts,
                               const JunctionDetectorOptions& junction_options, std::string* text);

}  // namespace sfm
