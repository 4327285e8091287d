// Measuring junctions and segment end-points against ground truth (docs/junction_results.md):
// used by benchmark_junctions and tests/junctions_e2e.
//
// - Generated sequences: the true image junctions of a frame from its truth (the visible wireframe
//   vertices, and the occlusion T's where a visible edge disappears behind a nearer face).
// - VGG Corridor: ground-truth junctions built from ground-truth segments whose ends meet.
// - One-to-one matching of detected to true points within a radius.
// - End-point offsets t (eq. 8 sign) of detected segments against true ones, for fitting eq. (5).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/junctions/junction.h"
#include "frontend/segments/line_segment.h"
#include "geometry/camera.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/wireframe.h"

namespace sfm {

// ---- Generated sequences ---------------------------------------------------------------------

struct TrueJunctionOptions {
  // A visible edge counts towards a vertex's detectability when its visible part, starting at the
  // vertex, is at least this long in the undistorted image (pixels).
  double min_edge_px = 10.0;
  // Two edges pointing within this of opposite ways are one straight line (radians; the
  // generator's own VisibilityOptions::collinear_tolerance, 8 degrees).
  double collinear_tolerance_rad = 0.14;
  // Optional image contrast of each visible segment of the frame (EdgeContrasts, same order as
  // FrameTruth::segments, grey levels). When given, a vertex is also judged contrast-detectable:
  // as detectable, counting only long edges whose contrast is at least min_contrast.
  const std::vector<double>* segment_contrast = nullptr;
  double min_contrast = 0;
  // When positive: the undistorted image's size. Each edge part then counts (for min_edge_px, and
  // its far end) only up to where it leaves the image, [-0.5, size - 0.5]. Without distortion the
  // truth's visible parts already end there; with barrel distortion the stored image sees beyond
  // the undistorted frame, so a part can run on outside the image the detector is given.
  int image_width = 0, image_height = 0;
  // When not null: min_edge_px is measured in this camera's stored (distorted) image, the chord
  // between the stored pixels of an edge part's ends, where the sensor resolves it. A wide lens's
  // undistorted periphery stretches an edge many times (1/cos^2 of the angle off axis for an
  // equidistant lens, 15x at 75 degrees): a 10 px undistorted edge there is under one stored pixel.
  const Camera* stored_camera = nullptr;
};

// A visible wireframe vertex where at least two visible edges meet, not just two collinear ones.
struct TrueVertexJunction {
  int vertex = -1;                                     // index into Wireframe::vertices
  Eigen::Vector2d location = Eigen::Vector2d::Zero();  // undistorted pixels
  int num_edges = 0;       // visible edges whose visible part starts at the vertex
  int num_long_edges = 0;  // of those, the ones at least min_edge_px long
  // Detectable: at least two long edges, not just two collinear ones. Only such a vertex can be
  // found by any detector that needs segments of some length; the benchmark's main recall is over
  // these.
  bool detectable = false;
  // Detectable counting only long edges of measurable image contrast (segment_contrast given and
  // each of at least min_contrast); equal to `detectable` when no contrasts are given.
  bool contrast_detectable = false;
  // Type of the junction the long edges form (detectable vertices), else of all visible edges.
  JunctionType type = JunctionType::kL;
  // The far ends of the long edges' visible parts (undistorted pixels).
  std::vector<Eigen::Vector2d> long_edge_ends;
};

struct FrameTrueJunctions {
  std::vector<TrueVertexJunction> vertices;
  // Occlusion T's: an end of a visible edge part (at least min_edge_px long) where a nearer face
  // hides the rest of the edge. The occluding contour passes there, so the image shows a T.
  std::vector<Eigen::Vector2d> occlusions;
};

// The true junctions of one frame of a generated sequence.
FrameTrueJunctions TrueJunctionsOfFrame(const Wireframe& wireframe, const FrameTruth& frame,
                                        const TrueJunctionOptions& options);

// The image contrast of the visible segments of one frame: for each of FrameTruth::segments, the
// mean absolute grey-level step I(p + offset n) - I(p - offset n) across the segment's line (n its
// unit normal, bilinear interpolation), sampled every pixel along it, leaving out end_margin_px at
// each end (other faces meet there). `image` is the undistorted 8-bit image, ideally rendered
// without noise (the benchmark renders a noise-free twin of each sequence). -1 for a segment with
// no sample (shorter than two end margins, or off the image), and for all when not CV_8UC1.
struct EdgeContrastOptions {
  double offset_px = 2.0;      // > blur (0.7 px) + anti-aliasing: the step is fully developed there
  double end_margin_px = 3.0;  // px left out at each end
};
std::vector<double> EdgeContrasts(const cv::Mat& image, const FrameTruth& frame, const EdgeContrastOptions& options);

// The visible part of a wireframe edge in one frame, as a segment of the undistorted image.
struct TrueSegment {
  LineSegment segment;  // p0 at the part's t[0] end
  SegmentEnd end[2] = {SegmentEnd::kBorder, SegmentEnd::kBorder};
  // The image edge really ends at this end: an occlusion, or a vertex where no other visible edge
  // continues the line (within collinear_tolerance_rad). Not the border, and not a vertex inside
  // a straight image edge (two collinear wireframe edges, as the bar of a T).
  bool real_end[2] = {false, false};
};
std::vector<TrueSegment> TrueSegmentsOfFrame(const Wireframe& wireframe, const FrameTruth& frame,
                                             const TrueJunctionOptions& options);

// ---- Junctions from ground-truth segments (VGG Corridor) -------------------------------------

struct SegmentJunctionOptions {
  double contact_px = 3.0;     // pixels: how close ends must come to meet (see JunctionsFromSegments)
  double min_angle_deg = 10;   // degrees: pairs of lines closer to parallel never form a junction
  double merge_px = 3.0;       // pixels: pair junctions this close are one junction (single linkage)
};

struct SegmentJunction {
  Eigen::Vector2d location = Eigen::Vector2d::Zero();
  std::vector<int> segments;  // indices of the segments that meet there, increasing
  JunctionType type = JunctionType::kL;
};

// Junctions of a set of (ground-truth) segments whose ends meet. Two segments at least
// min_angle_deg from parallel meet at the intersection p of their lines when an end-point of one
// of them lies within contact_px of p and p lies within contact_px of the other segment (its end
// or its interior): an L (end to end) or a T (end on interior). Two interiors crossing do not
// count ("whose ends meet"). Pair points within merge_px of one another (single linkage) are one
// junction at their mean; its segments are the union of the pairs', and its type comes from
// ClassifyJunction on junction segments to the far ends (both ends for a segment that p splits
// more than contact_px from either end).
std::vector<SegmentJunction> JunctionsFromSegments(const LineSegments& segments,
                                                   const SegmentJunctionOptions& options);

// ---- Matching ----------------------------------------------------------------------------------

struct PointMatch {
  int truth = -1, detected = -1;
  double distance = 0;
};

// One-to-one matching of detected to true points within `radius`: all pairs within it, closest
// first, each point used at most once. Sorted by truth index.
std::vector<PointMatch> MatchPoints(const std::vector<Eigen::Vector2d>& truth,
                                    const std::vector<Eigen::Vector2d>& detected, double radius);

// ---- End-point offsets -----------------------------------------------------------------------

struct EndpointOffsetOptions {
  double max_line_distance = 1.0;  // pixels: both detected end-points within this of the true line
  double max_angle_deg = 3.0;      // degrees: largest angle between detected and true segment
  double min_overlap_px = 5.0;     // pixels: a detection must overlap the true segment this much
  double min_true_length = 10.0;   // pixels: shorter true segments give no samples
  double max_abs_t = 20.0;         // pixels: larger |t| is a gross failure (missed or merged), not counted
};

struct EndpointOffsets {
  std::vector<double> t;  // eq. 8 sign: detected minus true along the outward direction, pixels
  int ends = 0;           // true ends considered
  int unmatched = 0;      // of those, with no compatible detection overlapping the true segment
  int gross = 0;          // of those, with |t| > max_abs_t
};

// For each end e of each true segment with use_end[e], the detection compatible with the true line
// (same line within max_line_distance at both its ends, within max_angle_deg) that overlaps the
// true segment and reaches farthest towards that end: t = its end-point's position minus the true
// end's, along the outward direction. A true segment detected in pieces thus gives each end the
// piece next to it. Appends to `offsets`.
void CollectEndpointOffsets(const LineSegments& detected, const LineSegment& truth, const bool use_end[2],
                            const EndpointOffsetOptions& options, EndpointOffsets* offsets);

}  // namespace sfm
