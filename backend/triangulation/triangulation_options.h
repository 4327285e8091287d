// Settings of point and line triangulation. docs/tracks_and_triangulation.md says how each default
// was chosen.
#pragma once

#include <cmath>
#include <string>

#include "frontend/util/status.h"

namespace sfm {

struct PointTriangulationOptions {
  // A track's largest angle between two of its viewing rays must exceed this; below it the depth
  // is set by noise. Degrees, in (0, 90).
  double min_parallax_deg = 1.5;
  // Largest reprojection error of the refined point in any view. Pixels, > 0.
  double max_reprojection_error_px = 4.0;
  // Gauss-Newton iterations after the linear solve; 0 keeps the linear solution. >= 0.
  int refinement_iterations = 10;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("PointTriangulationOptions: " + what); };
    if (!(min_parallax_deg > 0 && min_parallax_deg < 90)) return bad("min_parallax_deg must be in (0, 90)");
    if (!(max_reprojection_error_px > 0 && std::isfinite(max_reprojection_error_px))) {
      return bad("max_reprojection_error_px must be finite and > 0");
    }
    if (refinement_iterations < 0) return bad("refinement_iterations must be >= 0");
    return Status::Ok();
  }
};

struct LineTriangulationOptions {
  // The largest angle between two of a segment track's back-projected planes must exceed this;
  // below it the planes nearly coincide (the line lies close to the epipolar planes, e.g. parallel
  // to the motion) and their intersection is set by noise: the line is unobservable. Degrees, in
  // (0, 90).
  double min_plane_angle_deg = 3.0;
  // Largest distance, in any view, of an observed segment end (junction location or far end-point)
  // from the projected 3D line. Pixels, > 0.
  double max_reprojection_error_px = 4.0;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("LineTriangulationOptions: " + what); };
    if (!(min_plane_angle_deg > 0 && min_plane_angle_deg < 90))
      return bad("min_plane_angle_deg must be in (0, 90)");
    if (!(max_reprojection_error_px > 0 && std::isfinite(max_reprojection_error_px))) {
      return bad("max_reprojection_error_px must be finite and > 0");
    }
    return Status::Ok();
  }
};

struct TriangulationOptions {
  PointTriangulationOptions point;
  LineTriangulationOptions line;

  Status Check() const {
    SFM_RETURN_IF_ERROR(point.Check());
    return line.Check();
  }
};

}  // namespace sfm
