#include "backend/triangulation/wireframe_selection.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/line_triangulation.h"

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Callers first make sure there is something to test (degrees_of_freedom >= 1).
bool PassesChiSquare(double statistic, int degrees_of_freedom, double level) {
  return statistic <= ChiSquareQuantile(level, degrees_of_freedom);
}

double SmallestDepth(const std::vector<Pose3>& cameras, const Eigen::Vector3d& x) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Pose3& camera : cameras) smallest = std::min(smallest, (camera.Inverse() * x).z());
  return smallest;
}

// The line's extent measured again on `cameras` (the final poses) by BoundLine's rule: end0 at
// `junction_point` projected onto the line when there is one, else the median of the
// back-projected junction locations; end1 the median of the back-projected far ends. The
// landmark's own ends were bounded on the poses it was triangulated with (the odometry's) and
// bundle adjustment only slides them onto the refined line, so a pose correction of a few
// centimetres along the line stays in them. False when no segment of positive length in front of
// every camera results. The depth floor is not applied again (min_depth_m 0): the triangulation
// applied it.
bool BoundOnFinalPoses(const Eigen::Matrix3d& K, const std::vector<LineView>& views, const LineLandmark& line,
                       const Eigen::Vector3d* junction_point, Segment3* segment) {
  LineTriangulationOptions options;
  options.min_depth_m = 0;
  return BoundLine(K, views, Line3{line.point, line.direction}, junction_point, options, segment) == LineStatus::kOk;
}

// The probability that a vertex of worst-direction sigma lies within `tolerance` of its true
// position across the edge: its error there taken as a two-dimensional Gaussian with that sigma in
// both directions (Rayleigh), which no error with smaller sigmas in some direction exceeds.
double WithinTolerance(double sigma, double tolerance) {
  if (!(sigma > 0)) return 1;
  return 1 - std::exp(-tolerance * tolerance / (2 * sigma * sigma));
}

// WireframeOptions::tolerance_m: drops the landmarks of the least determined vertices, largest
// sigma first, until the predicted share of the remaining vertices within the tolerance is at least
// options.tolerance_share. A point takes the lines drawn from it with it (their edge starts at
// the point). point_sigma[i] is kept point i's sigma; end0_sigma[j] (negative: end0 is a point)
// and end1_sigma[j] kept line j's.
void DropBeyondTolerance(const WireframeOptions& options, const std::vector<double>& point_sigma,
                         const std::vector<double>& end0_sigma, const std::vector<double>& end1_sigma,
                         Landmarks* selected, WireframeSelectionReport* counts) {
  struct Vertex {
    double sigma;
    bool point;
    int index;
  };
  std::vector<Vertex> vertices;
  double expected = 0;
  for (size_t i = 0; i < point_sigma.size(); ++i) vertices.push_back({point_sigma[i], true, static_cast<int>(i)});
  for (size_t j = 0; j < end1_sigma.size(); ++j) {
    vertices.push_back({end1_sigma[j], false, static_cast<int>(j)});
    if (end0_sigma[j] >= 0) vertices.push_back({end0_sigma[j], false, static_cast<int>(j)});
  }
  for (const Vertex& v : vertices) expected += WithinTolerance(v.sigma, options.tolerance_m);
  int count = static_cast<int>(vertices.size());
  std::vector<std::vector<int>> lines_of_point(point_sigma.size());
  for (size_t j = 0; j < selected->lines.size(); ++j) {
    if (selected->lines[j].point_landmark >= 0) lines_of_point[selected->lines[j].point_landmark].push_back(j);
  }
  std::sort(vertices.begin(), vertices.end(), [](const Vertex& a, const Vertex& b) { return a.sigma > b.sigma; });
  std::vector<bool> point_dropped(point_sigma.size(), false), line_dropped(end1_sigma.size(), false);
  auto drop_line = [&](int j) {
    line_dropped[j] = true;
    expected -= WithinTolerance(end1_sigma[j], options.tolerance_m);
    --count;
    if (end0_sigma[j] >= 0) {
      expected -= WithinTolerance(end0_sigma[j], options.tolerance_m);
      --count;
    }
  };
  for (const Vertex& v : vertices) {
    if (count == 0 || expected >= options.tolerance_share * count) break;
    if (v.point ? point_dropped[v.index] : line_dropped[v.index]) continue;
    if (!v.point) {
      drop_line(v.index);
      continue;
    }
    point_dropped[v.index] = true;
    expected -= WithinTolerance(v.sigma, options.tolerance_m);
    --count;
    for (int j : lines_of_point[v.index]) {
      if (!line_dropped[j]) drop_line(j);
    }
  }
  Landmarks kept;
  std::vector<int> new_index(point_sigma.size(), -1);
  for (size_t i = 0; i < selected->points.size(); ++i) {
    if (point_dropped[i]) {
      ++counts->points_beyond_tolerance;
      continue;
    }
    new_index[i] = static_cast<int>(kept.points.size());
    kept.points.push_back(std::move(selected->points[i]));
  }
  for (size_t j = 0; j < selected->lines.size(); ++j) {
    if (line_dropped[j]) {
      ++counts->lines_beyond_tolerance;
      continue;
    }
    LineLandmark line = std::move(selected->lines[j]);
    if (line.point_landmark >= 0) line.point_landmark = new_index[line.point_landmark];
    kept.lines.push_back(std::move(line));
  }
  counts->predicted_share = count > 0 ? expected / count : 1;
  *selected = std::move(kept);
}

// The element at index size / 2 once sorted (the upper of the two middle ones for an even count).
double UpperMedian(std::vector<double> values) {
  auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// A landmark's residuals at sigma_px on world_T_camera: rule 1's consistency test, and the
// variance factors' chi2 / dof. Computed once per landmark, before the selection, since the
// variances of unit weight need every landmark's.
struct ResidualTest {
  double chi_square = 0;
  int dof = 0;
};

std::vector<ResidualTest> PointResidualTests(const Eigen::Matrix3d& K,
                                             const std::vector<Pose3>& world_T_camera,
                                             const Landmarks& landmarks, double sigma_px) {
  std::vector<ResidualTest> tests(landmarks.points.size());
  for (size_t i = 0; i < landmarks.points.size(); ++i) {
    const PointLandmark& point = landmarks.points[i];
    std::vector<Pose3> cameras;
    std::vector<Eigen::Vector2d> pixels;
    for (const PointObservation& observation : point.observations) {
      CHECK(observation.frame >= 0 && observation.frame < static_cast<int>(world_T_camera.size()))
          << "frame " << observation.frame;
      cameras.push_back(world_T_camera[observation.frame]);
      pixels.push_back(observation.pixel);
    }
    tests[i].chi_square = PointChiSquare(K, cameras, pixels, point.position, sigma_px, &tests[i].dof);
  }
  return tests;
}

std::vector<ResidualTest> LineResidualTests(const Eigen::Matrix3d& K,
                                            const std::vector<Pose3>& world_T_camera,
                                            const Landmarks& landmarks, double sigma_px) {
  std::vector<ResidualTest> tests(landmarks.lines.size());
  for (size_t i = 0; i < landmarks.lines.size(); ++i) {
    const LineLandmark& line = landmarks.lines[i];
    std::vector<LineSegmentView> views;
    for (const LineObservation& observation : line.observations) {
      CHECK(observation.frame >= 0 && observation.frame < static_cast<int>(world_T_camera.size()))
          << "frame " << observation.frame;
      views.push_back({world_T_camera[observation.frame], observation.p0, observation.p1, observation.frame});
    }
    tests[i].chi_square = LineChiSquare(K, views, line.point, line.direction, sigma_px, &tests[i].dof);
  }
  return tests;
}

// The variance of unit weight of a set of landmarks (each landmark's own variance
// factor, rule 2) from their residuals' chi2 / m(dof), m(k) the median of a chi-square
// variable with k degrees of freedom: the median of the ratios, so that landmarks whose residuals
// follow the noise model give 1 whatever their number of views, robust to the wrong tracks and
// groupings among them. 1 when there is none, or when the median is 0 (noise-free observations).
double UnitVariance(const std::vector<ResidualTest>& tests) {
  std::vector<double> ratios;
  for (const ResidualTest& test : tests) {
    if (test.dof >= 1 && std::isfinite(test.chi_square)) {
      ratios.push_back(test.chi_square / ChiSquareQuantile(0.5, test.dof));
    }
  }
  const double median = ratios.empty() ? 0.0 : UpperMedian(std::move(ratios));
  return median > 0 ? median : 1.0;
}

// A landmark's own a-posteriori variance factor relative to its kind's variance of unit weight, as
// a factor on its sigmas: sqrt(chi2 / dof / unit_variance) when above 1, else 1 (never below the
// first-order sigma). 1 without a degree of freedom.
double OwnSigmaFactor(double chi_square, int dof, double unit_variance) {
  if (dof < 1) return 1.0;
  return std::sqrt(std::max(1.0, chi_square / dof / unit_variance));
}

// WireframeOptions::far_end_at_point_px: a kept line's end1 at the drawn point whose projections
// lie on the line's observed image lines (median distance across, over its views, <=
// far_end_at_point_px) at its observed far ends (median distance along <= far_end_along_px),
// ahead of the line's start within far_end_max_angle_deg; the best such point by the sum of the
// two medians relative to their bounds. Runs after every other rule: the points are final.
void FarEndsAtPoints(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                     const WireframeOptions& options, Landmarks* selected, WireframeSelectionReport* counts) {
  const double cos_max = std::cos(options.far_end_max_angle_deg * kPi / 180);
  for (LineLandmark& line : selected->lines) {
    const Eigen::Vector3d start =
        line.point_landmark >= 0 ? selected->points[line.point_landmark].position : line.end0;
    const Eigen::Vector3d along = line.end1 - start;
    if (!(along.norm() > 0)) continue;
    int best = -1;
    double best_cost = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < selected->points.size(); ++i) {
      if (static_cast<int>(i) == line.point_landmark) continue;
      const Eigen::Vector3d& x = selected->points[i].position;
      const Eigen::Vector3d to_point = x - start;
      if (!(to_point.norm() > 0) || to_point.normalized().dot(along.normalized()) < cos_max) continue;
      std::vector<double> across, along_px;
      bool in_front = true;
      for (const LineObservation& observation : line.observations) {
        const Eigen::Vector3d in_camera = world_T_camera[observation.frame].Inverse() * x;
        const Eigen::Vector2d d = observation.p1 - observation.p0;
        if (!(in_camera.z() > 0 && d.norm() > 0)) {
          in_front = false;
          break;
        }
        const Eigen::Vector2d t = d.normalized();
        const Eigen::Vector2d r = (K * in_camera).hnormalized() - observation.p1;
        across.push_back(std::abs(t.x() * r.y() - t.y() * r.x()));
        along_px.push_back(std::abs(t.dot(r)));
      }
      if (!in_front || across.empty()) continue;
      const double a = UpperMedian(across), b = UpperMedian(along_px);
      if (a > options.far_end_at_point_px || b > options.far_end_along_px) continue;
      const double cost = a / options.far_end_at_point_px + b / options.far_end_along_px;
      if (cost < best_cost) best = static_cast<int>(i), best_cost = cost;
    }
    if (best < 0) continue;
    line.end1 = selected->points[best].position;
    line.end1_point = best;
    ++counts->lines_far_end_at_point;
  }
}

}  // namespace

double MaxVertexSigma(const WireframeOptions& options, double fx, double depth) {
  return std::sqrt(2.0) * options.pixel_sigma_px / fx * depth /
         std::tan(options.min_equivalent_parallax_deg * kPi / 180);
}

PoseDrift WireframePoseDrift(const WireframeOptions& options, const std::vector<Pose3>& world_T_camera) {
  std::vector<double> steps;
  for (size_t f = 1; f < world_T_camera.size(); ++f) {
    steps.push_back((world_T_camera[f].translation - world_T_camera[f - 1].translation).norm());
  }
  const double median_step = steps.empty() ? 0 : UpperMedian(std::move(steps));
  return PoseDrift{options.pose_rotation_step_rad, options.pose_translation_step_fraction * median_step};
}

double EstimatePixelSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const Landmarks& landmarks) {
  std::vector<double> components;
  for (const PointLandmark& point : landmarks.points) {
    for (const PointObservation& observation : point.observations) {
      CHECK(observation.frame >= 0 && observation.frame < static_cast<int>(world_T_camera.size()))
          << "frame " << observation.frame;
      const Eigen::Vector3d in_camera = world_T_camera[observation.frame].Inverse() * point.position;
      if (!(in_camera.z() > 0)) continue;
      const Eigen::Vector3d projected = K * in_camera;
      const Eigen::Vector2d residual = projected.hnormalized() - observation.pixel;
      components.push_back(std::abs(residual.x()));
      components.push_back(std::abs(residual.y()));
    }
  }
  if (components.empty()) return 0;
  // The median absolute deviation of a zero-mean Gaussian is 0.6745 sigma.
  return 1.4826 * UpperMedian(std::move(components));
}

Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const WireframeOptions& options,
                                   WireframeSelectionReport* report) {
  return SelectWireframeLandmarks(K, world_T_camera, landmarks, std::vector<Junctions>(), options, report);
}

Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const std::vector<Junctions>& junctions,
                                   const WireframeOptions& options, WireframeSelectionReport* report) {
  return SelectWireframeLandmarks(K, world_T_camera, landmarks, junctions, options,
                                  WireframePoseDrift(options, world_T_camera), report);
}

Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const std::vector<Junctions>& junctions,
                                   const WireframeOptions& options, const PoseDrift& drift,
                                   WireframeSelectionReport* report) {
  CHECK(options.Check().ok()) << options.Check().message();
  const double sigma_px =
      options.estimate_pixel_sigma
          ? std::max(options.pixel_sigma_px, EstimatePixelSigma(K, world_T_camera, landmarks))
          : options.pixel_sigma_px;
  const double fx = K(0, 0);
  auto camera = [&world_T_camera](int frame) -> const Pose3& {
    CHECK(frame >= 0 && frame < static_cast<int>(world_T_camera.size())) << "frame " << frame;
    return world_T_camera[frame];
  };
  // A vertex is determined when its sigma is within the bound at its smallest depth (> 0). The
  // bound takes the same pixel noise as the sigma, so that the pixel part of the test does not
  // depend on the noise level (only the pose drift's share does).
  WireframeOptions bound_options = options;
  bound_options.pixel_sigma_px = sigma_px;
  auto determined = [&](double sigma, double depth) {
    return depth > 0 && sigma <= MaxVertexSigma(bound_options, fx, depth);
  };
  WireframeSelectionReport counts;
  const std::vector<ResidualTest> point_tests = PointResidualTests(K, world_T_camera, landmarks, sigma_px);
  const std::vector<ResidualTest> line_tests = LineResidualTests(K, world_T_camera, landmarks, sigma_px);
  // The points' and the lines' variances of unit weight: each landmark's sigma is scaled by its own
  // a-posteriori variance factor relative to its kind's, when above 1 (Foerstner & Wrobel 2016,
  // "Photogrammetric Computer Vision", ch. 4; docs/tracks_and_triangulation.md, "A line's own
  // variance factor").
  const double point_unit_variance = UnitVariance(point_tests);
  const double line_unit_variance = UnitVariance(line_tests);
  Landmarks selected;
  std::vector<int> new_index(landmarks.points.size(), -1);
  // The drawn vertices' sigmas, for the accuracy asked (tolerance_m): kept points', and kept lines'
  // end0 (negative when it is a point) and end1.
  std::vector<double> point_sigmas, end0_sigmas, end1_sigmas;
  for (size_t i = 0; i < landmarks.points.size(); ++i) {
    const PointLandmark& point = landmarks.points[i];
    std::vector<Pose3> cameras;
    std::vector<int> frames;
    for (const PointObservation& observation : point.observations) {
      cameras.push_back(camera(observation.frame));
      frames.push_back(observation.frame);
    }
    const auto [chi_square, dof] = point_tests[i];
    if (dof < 1) {  // one view left (bundle adjustment removed the others): nothing to test
      ++counts.points_untestable;
      continue;
    }
    if (!PassesChiSquare(chi_square, dof, options.consistency_level)) {
      ++counts.points_inconsistent;
      continue;
    }
    if (!junctions.empty() && SeenAsTOrX(junctions, point) &&
        static_cast<int>(point.observations.size()) < options.occlusion_candidate_min_views) {
      ++counts.points_occlusion_untested;
      continue;
    }
    // The point's own variance factor, as for the lines below.
    const double point_factor = OwnSigmaFactor(chi_square, dof, point_unit_variance);
    const double point_sigma =
        point_factor * PointPositionSigma(K, cameras, frames, point.position, sigma_px, drift);
    if (!determined(point_sigma, SmallestDepth(cameras, point.position))) {
      ++counts.points_uncertain;
      continue;
    }
    point_sigmas.push_back(point_sigma);
    new_index[i] = static_cast<int>(selected.points.size());
    selected.points.push_back(point);
  }
  for (size_t l = 0; l < landmarks.lines.size(); ++l) {
    const LineLandmark& line = landmarks.lines[l];
    std::vector<LineSegmentView> views;
    std::vector<LineView> line_views;
    std::vector<Pose3> cameras;
    for (const LineObservation& observation : line.observations) {
      views.push_back({camera(observation.frame), observation.p0, observation.p1, observation.frame});
      line_views.push_back({camera(observation.frame), observation.p0, observation.p1});
      cameras.push_back(camera(observation.frame));
    }
    const auto [chi_square, dof] = line_tests[l];
    // Two views of a line always meet in one (their planes intersect): a track that pairs two
    // different edges passes an empty test. Only tested tracks are drawn: a two-view line only
    // when its junction point was kept, i.e. the junction correspondence passed the point's test
    // (1 degree of freedom, the epipolar constraint); the matcher pairs a junction's segments
    // with its location (one shift for all of them). A two-view T or X is not kept: its location
    // need not be one 3D point even when matched right, so its test checks no correspondence.
    if (dof < 1 && (line.point_landmark < 0 || new_index[line.point_landmark] < 0)) {
      ++counts.lines_untestable;
      continue;
    }
    if (dof >= 1 && !PassesChiSquare(chi_square, dof, options.consistency_level)) {
      ++counts.lines_inconsistent;
      continue;
    }
    LineLandmark kept = line;
    kept.point_landmark = line.point_landmark >= 0 ? new_index[line.point_landmark] : -1;
    // A dropped point is not the line's end (it may lie off the line): the line's own junction
    // end is used instead.
    const Eigen::Vector3d* junction_point =
        kept.point_landmark >= 0 ? &landmarks.points[line.point_landmark].position : nullptr;
    Segment3 segment;
    if (!BoundOnFinalPoses(K, line_views, line, junction_point, &segment)) {
      ++counts.lines_unbounded;
      continue;
    }
    kept.direction = (segment.end1 - segment.end0).normalized();
    kept.end0 = kept.point_landmark >= 0 ? line.end0 : segment.end0;
    kept.end1 = segment.end1;
    // The line's own variance factor: its residuals' chi2 / dof relative to the lines' typical one,
    // when above 1, scales its covariance (both vertices' sigmas by the square root).
    const double factor = OwnSigmaFactor(chi_square, dof, line_unit_variance);
    // line_end_along_sigma: a back-projected end's rule-2 sigma is the worse of across and along
    // the line (LineEndAlongSigma), the along part from the same across sigma and pixel noise.
    auto end_sigma = [&](const Eigen::Vector3d& end, bool along) {
      const double across = factor * LinePositionSigma(K, views, end, kept.direction, sigma_px, drift,
                                                       options.line_sigma_subtracts_plane_noise);
      if (!along) return across;
      return std::max(across, LineEndAlongSigma(K, views, end, kept.direction, factor * sigma_px, across));
    };
    const double end0_sigma =
        kept.point_landmark < 0 ? end_sigma(kept.end0, options.line_end_along_sigma >= 1) : -1;
    if (kept.point_landmark < 0 && !determined(end0_sigma, SmallestDepth(cameras, kept.end0))) {
      ++counts.lines_uncertain_end0;
      continue;
    }
    const double end1_sigma = end_sigma(kept.end1, options.line_end_along_sigma >= 2);
    if (!determined(end1_sigma, SmallestDepth(cameras, kept.end1))) {
      ++counts.lines_uncertain_end1;
      continue;
    }
    end0_sigmas.push_back(end0_sigma);
    end1_sigmas.push_back(end1_sigma);
    selected.lines.push_back(std::move(kept));
  }
  if (options.tolerance_m > 0) {
    DropBeyondTolerance(options, point_sigmas, end0_sigmas, end1_sigmas, &selected, &counts);
  }
  if (options.far_end_at_point_px > 0) FarEndsAtPoints(K, world_T_camera, options, &selected, &counts);
  counts.pixel_sigma_px = sigma_px;
  counts.points_kept = static_cast<int>(selected.points.size());
  counts.lines_kept = static_cast<int>(selected.lines.size());
  if (report != nullptr) *report = counts;
  return selected;
}

}  // namespace sfm
