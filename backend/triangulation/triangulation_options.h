// Settings of point and line triangulation. docs/tracks_and_triangulation.md says how each default
// was chosen.
#pragma once

#include <cmath>
#include <string>

#include "frontend/junctions/junction.h"
#include "util/status.h"

namespace sfm {

// Least depth of a landmark in a view that observes it, metres: twice the generator's near
// clipping plane (0.05 m); nothing a robot's camera sees sharply is closer, and a track whose views
// share one centre (no motion, odometry noise of a millimetre) is intersected next to that centre.
// The default of every stage's depth floor (triangulation, track extension, bundle adjustment).
inline constexpr double kMinDepthM = 0.1;

struct PointTriangulationOptions {
  // A track's largest angle between two of its viewing rays must exceed this; below it the depth
  // is set by noise. Degrees, in (0, 90).
  double min_parallax_deg = 1.5;
  // Largest reprojection error of the refined point in any view. Pixels, > 0.
  double max_reprojection_error_px = 4.0;
  // Gauss-Newton iterations after the linear solve; 0 keeps the linear solution. >= 0.
  int refinement_iterations = 10;
  // The point must be at least this deep (z in the camera frame) in every view, else kTooClose.
  // Metres, >= 0.
  double min_depth_m = kMinDepthM;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("PointTriangulationOptions: " + what); };
    if (!(min_parallax_deg > 0 && min_parallax_deg < 90)) return bad("min_parallax_deg must be in (0, 90)");
    if (!(max_reprojection_error_px > 0 && std::isfinite(max_reprojection_error_px))) {
      return bad("max_reprojection_error_px must be finite and > 0");
    }
    if (refinement_iterations < 0) return bad("refinement_iterations must be >= 0");
    if (!(min_depth_m >= 0 && std::isfinite(min_depth_m))) return bad("min_depth_m must be finite and >= 0");
    return Status::Ok();
  }
};

struct LineTriangulationOptions {
  // The largest angle between two of a segment track's back-projected planes must exceed this;
  // below it the planes nearly coincide (the line lies close to the epipolar planes, e.g. parallel
  // to the motion) and their intersection is set by noise: the line is unobservable. Degrees, in
  // (0, 90).
  double min_plane_angle_deg = 3.0;
  // The camera centres must spread across the measured planes by more than this, seen from the
  // intersected line (MaxCentreSpreadAngle): noise tilts the planes but cannot move the centres off
  // them, so with coincident centres the spread is 0 whatever the noise, while MaxPlaneAngle can
  // pass on noise alone. Without noise both angles are equal; half of min_plane_angle_deg, so that
  // it only removes lines whose plane angle is mostly noise. With the line at least min_depth_m
  // from every centre (0.1 m), no baseline below 2.6 mm passes. Degrees, in (0, 90).
  double min_centre_spread_deg = 1.5;
  // Largest distance, in any view, of an observed segment end (junction location or far end-point)
  // from the projected 3D line. Pixels, > 0.
  double max_reprojection_error_px = 4.0;
  // The line must pass at least this far from every camera centre, and both ends of the bounded
  // segment must be at least this deep in every view, else kTooClose. Metres, >= 0.
  double min_depth_m = kMinDepthM;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("LineTriangulationOptions: " + what); };
    if (!(min_plane_angle_deg > 0 && min_plane_angle_deg < 90))
      return bad("min_plane_angle_deg must be in (0, 90)");
    if (!(min_centre_spread_deg > 0 && min_centre_spread_deg < 90))
      return bad("min_centre_spread_deg must be in (0, 90)");
    if (!(max_reprojection_error_px > 0 && std::isfinite(max_reprojection_error_px))) {
      return bad("max_reprojection_error_px must be finite and > 0");
    }
    if (!(min_depth_m >= 0 && std::isfinite(min_depth_m))) return bad("min_depth_m must be finite and >= 0");
    return Status::Ok();
  }
};

// Which landmarks the wireframe shows (SelectWireframeLandmarks, wireframe_selection.h), judged on
// the final poses. docs/tracks_and_triangulation.md, "Wireframe vertices", says why each default.
struct WireframeOptions {
  // Pixel noise of a junction location and across an image segment's end. Pixels, > 0: the
  // junction detector's location error on rendered images.
  double pixel_sigma_px = kJunctionLocationErrorPx;
  // Real images are noisier than rendered ones, and the detector's error there is not known in
  // advance: when true, the noise of the chi-square test is the larger of pixel_sigma_px and the
  // robust scale of the points' own reprojection residuals on the final poses (EstimatePixelSigma),
  // so pixel_sigma_px acts as a floor. The determination test does not depend on the noise (both
  // sides scale with it).
  bool estimate_pixel_sigma = true;
  // A landmark's residuals must pass the chi-square test at this level (its observations agree
  // with one 3D point or line to within the pixel noise), else it is not drawn. In (0, 1).
  double consistency_level = 0.999;
  // A vertex is drawn only when it is determined at least as well, relative to its depth, as a
  // point seen in two views whose rays meet at this angle: sigma <= sqrt(2) (pixel_sigma_px / f)
  // depth / tan(angle), sigma the first-order standard deviation of its position across the
  // worst direction, depth its smallest in a view that sees it, f = fx. Degrees, in (0, 90).
  double min_equivalent_parallax_deg = 1.5;
  // The final poses' rotation error as the determination test models it (PoseDrift,
  // landmark_uncertainty.h): a random walk along the frame index with this standard deviation per
  // axis and per frame. A vertex's sigma is then its pixel-noise sigma plus the rotations' error
  // carried through its geometry, held to the same MaxVertexSigma. Radians, >= 0 (0: pixel noise
  // only). 0.0002: the refined trajectories' rotation RPE on the generated sequences,
  // 0.00032-0.00038 rad per frame (docs/backend_results.md, an angle: sqrt(3) x the per-axis
  // sigma), i.e. what bundle adjustment leaves of the odometry's 0.002 rad per frame. Not a
  // measure of the wireframe. A pipeline that knows its poses better or worse sets it.
  double pose_rotation_step_rad = 0.0002;
  // The final poses' camera-centre error, the same kind of random walk, per axis per frame, as a
  // fraction of the median distance between consecutive camera centres (so that it is in the
  // scene's own units and scales with the robot's speed: a sequence in millimetres, or one taken
  // twice as fast, gets the same rule), >= 0 (0: none). 0.003: the refined trajectories' translation
  // RPE on the generated sequences with the default odometry noise, 0.0008-0.0013 m per frame on
  // steps of 0.1-0.2 m (an RMS length: sqrt(3) x the per-axis sigma, so 0.0023-0.0038 of the 0.2 m
  // corridor steps). Like the rotation's, a property of the refinement.
  double pose_translation_step_fraction = 0.003;
  // A point whose junction is a T or an X in some view is an occlusion candidate: its location may
  // be where a nearer edge crosses a farther one in the image, which slides along the edges as the
  // camera moves and is no 3D point. With two views the point's test has one degree of freedom
  // (the epipolar constraint), blind to a slide along the epipolar line, which moves the point
  // along its viewing ray; and it is no test of the junction correspondence either (a right match
  // need not pass, a wrong one can). So such a point, and with it its two-view lines (rule 0), is
  // drawn only with at least this many views: three are the fewest in which a point's position
  // along one view's epipolar line is predicted by the others. The types are known only when
  // SelectWireframeLandmarks is given the junctions. >= 2 (2: no extra rule).
  // docs/tracks_and_triangulation.md, "Occlusion candidates".
  int occlusion_candidate_min_views = 3;
  // The line vertex sigma subtracts the plane normals' own noise from the information it measures
  // (LinePositionSigma's subtract_plane_noise): a line whose planes' spread is no more than the
  // end-points' noise makes is undetermined, however its noisy estimate happens to look.
  // docs/tracks_and_triangulation.md, "Plane noise in the line sigma".
  bool line_sigma_subtracts_plane_noise = true;
  // An accuracy the user asks of the drawn map, in the world's units: at least tolerance_share of
  // the drawn vertices within tolerance_m of their true position, as the vertex sigmas predict it.
  // The rules above are relative to depth (a vertex 6 m away may be off by 20 cm and pass); with
  // tolerance_m > 0 the least determined vertices are then dropped, largest sigma first, until the
  // predicted share of drawn vertices within tolerance_m is at least tolerance_share (a vertex
  // within it with probability 1 - exp(-tolerance_m^2 / (2 sigma^2)): its error across the true
  // edge as a two-dimensional Gaussian of its worst-direction sigma in both directions, an upper
  // bound on its miss probability). Nothing is dropped where the prediction already meets the
  // share. 0: off. docs/tracks_and_triangulation.md, "An accuracy asked of the map".
  double tolerance_m = 0;
  double tolerance_share = 0.9;  // in (0, 1)
  // A drawn line's far end taken at a drawn junction point (0: off). The point is
  // measured directly in each of its views; the line's far end is the intersection of the 3D line
  // (whose direction a biased image segment tilts) with the far end-point's viewing ray, an
  // extrapolation. When a drawn point (not the line's own) projects, in the line's views, onto the
  // observed image lines (median distance across them <= far_end_at_point_px) at the observed far
  // end-points (median distance along them <= far_end_along_px), and lies ahead of the line's
  // start (its junction point, else end0) within far_end_max_angle_deg of the segment, end1 is
  // that point's position, a vertex of the edge's own (sharing the point's vertex lowered the
  // share: the far ends it merges into points are mostly within 5 cm; docs/decisions.md).
  // docs/tracks_and_triangulation.md, "Far ends at junction points". Default 1 px: about 3 sigma
  // of the 0.3 px pixel noise the wireframe's tests use (3 px moves more far ends but breaks two to
  // three times as many good ones).
  double far_end_at_point_px = 1;
  double far_end_along_px = 5;
  double far_end_max_angle_deg = 15;
  // Rule 2 with a line end's position *along* the line . A back-projected end (end0 of a
  // line without a kept junction point: its junction locations; end1: its far end-points) is where
  // the viewing rays meet the 3D line, so it slides along the line by the line's own error across
  // itself divided by the sine of the ray-line angle, and by the pixel noise over the image speed
  // of a point moving along the line (LineEndAlongSigma). The rule-2 sigma of such an end becomes
  // the larger of its across and along sigmas (the worst direction, as for points). 0: off (across
  // only); 1 (default): the own end0 only, where the failure was measured (66-75 % of the own end0s seen within 10 degrees of end-on were beyond 5
  // cm on the held-out turns corridors); 2: end0 and end1. docs/tracks_and_triangulation.md, "A
  // line end's position along the line"; docs/decisions.md.
  int line_end_along_sigma = 1;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("WireframeOptions: " + what); };
    if (occlusion_candidate_min_views < 2) return bad("occlusion_candidate_min_views must be >= 2");
    if (!(pixel_sigma_px > 0 && std::isfinite(pixel_sigma_px))) return bad("pixel_sigma_px must be finite and > 0");
    if (!(consistency_level > 0 && consistency_level < 1)) return bad("consistency_level must be in (0, 1)");
    if (!(tolerance_m >= 0 && std::isfinite(tolerance_m))) return bad("tolerance_m must be finite and >= 0");
    if (line_end_along_sigma < 0 || line_end_along_sigma > 2) {
      return bad("line_end_along_sigma must be 0, 1 or 2");
    }
    if (!(tolerance_share > 0 && tolerance_share < 1)) return bad("tolerance_share must be in (0, 1)");
    if (!(far_end_at_point_px >= 0 && std::isfinite(far_end_at_point_px))) {
      return bad("far_end_at_point_px must be finite and >= 0");
    }
    if (!(far_end_along_px > 0 && std::isfinite(far_end_along_px))) return bad("far_end_along_px must be finite and > 0");
    if (!(far_end_max_angle_deg > 0 && far_end_max_angle_deg <= 90)) {
      return bad("far_end_max_angle_deg must be in (0, 90]");
    }
    if (!(min_equivalent_parallax_deg > 0 && min_equivalent_parallax_deg < 90)) {
      return bad("min_equivalent_parallax_deg must be in (0, 90)");
    }
    if (!(pose_rotation_step_rad >= 0 && std::isfinite(pose_rotation_step_rad))) {
      return bad("pose_rotation_step_rad must be finite and >= 0");
    }
    if (!(pose_translation_step_fraction >= 0 && std::isfinite(pose_translation_step_fraction))) {
      return bad("pose_translation_step_fraction must be finite and >= 0");
    }
    return Status::Ok();
  }
};

struct TriangulationOptions {
  PointTriangulationOptions point;
  LineTriangulationOptions line;
  WireframeOptions wireframe;

  Status Check() const {
    SFM_RETURN_IF_ERROR(point.Check());
    SFM_RETURN_IF_ERROR(line.Check());
    return wireframe.Check();
  }
};

}  // namespace sfm
