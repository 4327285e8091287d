// Sub-pixel localisation of a magnitude maximum across an edge (Devernay 1995), shared by the fast
// path's chain points and its branch search.
#pragma once

#include <optional>

namespace sfm {

// The offset from the middle sample of the vertex of the parabola through (-1, before),
// (0, centre), (1, after): when the middle sample is a maximum of a curved profile, within half a
// sample of it; otherwise nullopt (no peak to localise).
inline std::optional<double> ParabolaPeakOffset(double before, double centre, double after) {
  const double curvature = before - 2 * centre + after;
  if (!(centre >= before && centre >= after && curvature < 0)) return std::nullopt;
  return 0.5 * (before - after) / curvature;
}

}  // namespace sfm
