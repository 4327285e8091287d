// Command-line flags that several apps share: the segment detector's, the junction detector's and
// the matcher's, each defined once, with functions that copy them into the option structs.
//
// The flags come in groups, one .cc and one object library each (sfm_app/CMakeLists.txt), because
// the apps take different sets (benchmark_junctions's --segments is a list). An app takes exactly
// the flags of the groups it links. A concept has one flag name in every app: the junction
// detector's group and the matching group both name the end-point model --endpoint_lambda /
// --endpoint_mu and the threshold --junction_min_probability (no app links both).
// Object libraries, not static ones: a static library's object whose symbols an app never used
// would be dropped by the linker, and its flags with it. Each flag's default is the option
// struct's default.
#pragma once

#include <gflags/gflags.h>

#include <string>

#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/matching/matching_options.h"
#include "frontend/segments/segment_detector.h"

// --segments as given, for the apps that print it (group sfm_flags_segment_method; benchmark_junctions
// defines its own --segments, a list, which this declaration matches as well).
DECLARE_string(segments);

namespace sfm {

// Group sfm_flags_segment_method: --segments (fast | reference). False, with a one-line message
// in *error, for another name.
bool SegmentMethodFromFlags(SegmentDetectorOptions* options, std::string* error);

// Group sfm_flags_undistort: --undistort_interpolation (linear | cubic | lanczos4; default
// kDetectionInterpolation, linear). False, with a one-line message in *error, for another
// name.
bool UndistortInterpolationFromFlags(UndistortInterpolation* interpolation, std::string* error);
// Same group: --undistort_full_view (default kDetectionView, the full view).
UndistortView UndistortViewFromFlags();

// Group sfm_flags_junction_detector: --endpoint_lambda, --endpoint_mu, --junction_min_probability,
// --max_gap_px, --collinear_tolerance_deg, --collinear_max_offset_px, --min_arm_px.
void JunctionDetectorFromFlags(JunctionDetectorOptions* options);

// Group sfm_flags_matching: --endpoint_lambda and --endpoint_mu (the end-point model of both
// junction detection and matching), --junction_min_probability, --match_max_distance,
// --match_tau1, --match_tau2, --match_rho1, --match_pose_band, --match_band_sigmas,
// --match_cheirality, --match_topology. False, with a one-line message in *error, for a
// --match_rho1 that is not one of the choices.
bool MatchingFromFlags(JunctionDetectorOptions* junctions, MatchingOptions* matching, std::string* error);

// Group sfm_flags_matching_refine: --match_refine, --match_refine_gate, --match_refine_min_inliers.
void MatchingRefineFromFlags(MatchingOptions* matching);

}  // namespace sfm
