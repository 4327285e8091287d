// Does the ground truth describe the image the renderer drew? The truth files (visibility.cc)
// project the wireframe with Camera::Project; the images come from the z-buffer canvas, looked up
// through Camera::UndistortPixel at every supersample. The two paths share nothing past the camera
// model, so these tests measure, in written noise-free images, where each truth edge actually is:
// the mid-level crossing of the step profile across the truth's (curved, in a distorted image)
// edge. A wrong distortion direction, an inaccurate undistortion, a pixel-centre mistake in the
// supersampling, a z-buffer or clipping fault moves that crossing; each rendered corner, from the
// two edges beside it, is compared with the vertex pixel the truth file states.
//
// Figures and the case that prompted them: docs/generator.md, "Truth against the rendered image".
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/image_undistorter.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/sequence_writer.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

// How a step is read. The profile runs from -reach to +reach px across the edge; each side's level
// is the mean over [plateau, reach], beyond the blur and the 1 px anti-aliasing box.
struct ProbeSettings {
  double reach = 4.0;  // default renderer: blur sigma 0.7 px, so 3 sigma + 0.5 px = 2.6 px < 3
  double plateau = 3.0;
  // A probe is used only where no other truth edge passes within reach + 1 px: a second step inside
  // the profile would move the crossing, and the plateaus need not notice it.
  double Isolation() const { return reach + 1.0; }
};

constexpr double kStep = 0.05;             // px between profile samples
constexpr double kMinContrast = 12;        // grey levels between the two sides
constexpr double kMaxPlateauSpread = 1.5;  // grey levels: 8-bit rounding of a flat face, plus margin
constexpr double kEndMargin = 5;           // px: probes keep this far from a segment's ends...
constexpr double kCornerReach = 15;        // ...and those closer than this to a vertex end measure its corner

// Which image is compared with which projection: the stored image with Camera::Project (what the
// truth files call u_dist v_dist), or that image undistorted by ImageUndistorter (what the
// junction benchmark detects in) with ProjectUndistorted (u v).
struct Geometry {
  Camera camera;
  bool undistorted = false;

  Eigen::Vector2d Project(const Eigen::Vector3d& point_camera) const {
    return undistorted ? camera.ProjectUndistorted(point_camera) : camera.Project(point_camera);
  }
  const Eigen::Vector2d& End(const VisibleSegment& s, int i) const {
    return undistorted ? s.pixel[i] : s.pixel_distorted[i];
  }
  const Eigen::Vector2d& Vertex(const VisibleVertex& v) const {
    return undistorted ? v.pixel : v.pixel_distorted;
  }
  // Whether everything within `radius` of `p` shows the scene (the undistorted image is black where
  // the stored image has no pixel). Barrel distortion shrinks distances near the border, so a
  // margin in the stored image is a larger one in the undistorted image.
  bool Inside(const Eigen::Vector2d& p, double radius) const {
    const double margin = radius + 2;
    auto in_image = [&](const Eigen::Vector2d& q) {
      return q.x() >= margin && q.y() >= margin && q.x() <= camera.width - 1 - margin &&
             q.y() <= camera.height - 1 - margin;
    };
    return in_image(p) && (!undistorted || in_image(camera.DistortPixel(p)));
  }
};

double Bilinear(const cv::Mat& image, const Eigen::Vector2d& p) {
  const int x0 = static_cast<int>(std::floor(p.x())), y0 = static_cast<int>(std::floor(p.y()));
  const double fx = p.x() - x0, fy = p.y() - y0;
  auto at = [&](int x, int y) { return static_cast<double>(image.at<unsigned char>(y, x)); };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

// Offset (px, along `normal`) of the rendered edge from `pixel`: where the profile crosses the mean
// of its two plateaus. Nothing when the profile is not one clean step.
std::optional<double> EdgeOffset(const cv::Mat& image, const Eigen::Vector2d& pixel,
                                 const Eigen::Vector2d& normal, const ProbeSettings& settings) {
  const int n = static_cast<int>(std::lround(settings.reach / kStep));
  const int plateau = static_cast<int>(std::lround(settings.plateau / kStep));
  std::vector<double> profile(2 * n + 1);
  for (int k = -n; k <= n; ++k) profile[k + n] = Bilinear(image, pixel + k * kStep * normal);
  auto side = [&](int sign, double* mean) {
    double lo = 1e9, hi = -1e9, sum = 0;
    for (int k = plateau; k <= n; ++k) {
      const double v = profile[sign * k + n];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      sum += v;
    }
    *mean = sum / (n - plateau + 1);
    return hi - lo <= kMaxPlateauSpread;
  };
  double minus = 0, plus = 0;
  if (!side(-1, &minus) || !side(+1, &plus) || std::abs(plus - minus) < kMinContrast) return std::nullopt;
  const double mid = 0.5 * (minus + plus);
  std::vector<double> crossings;
  for (int k = -plateau; k < plateau; ++k) {
    const double a = profile[k + n] - mid, b = profile[k + 1 + n] - mid;
    if ((a < 0) != (b < 0)) crossings.push_back((k + a / (a - b)) * kStep);
  }
  if (crossings.size() != 1) return std::nullopt;
  return crossings.front();
}

// The truth's visible segments drawn into a per-pixel list of edge ids (a point every 1/6 px or
// closer): which edges pass near a pixel.
class EdgeMap {
 public:
  EdgeMap(const Geometry& geometry, const Pose3& camera_T_world, const Wireframe& wireframe,
          const std::vector<VisibleSegment>& segments)
      : width_(geometry.camera.width),
        height_(geometry.camera.height),
        edges_(static_cast<size_t>(width_) * height_) {
    for (const VisibleSegment& s : segments) {
      const WireEdge& edge = wireframe.edges[s.edge];
      const Eigen::Vector3d a = camera_T_world * wireframe.vertices[edge.vertex_a];
      const Eigen::Vector3d b = camera_T_world * wireframe.vertices[edge.vertex_b];
      // 6 points per px of the chord: at least 4 per px along the (longer, curved or perspective)
      // image curve.
      const int count = static_cast<int>(std::ceil(6 * (geometry.End(s, 1) - geometry.End(s, 0)).norm())) + 2;
      for (int k = 0; k <= count; ++k) {
        const double t = s.t[0] + (s.t[1] - s.t[0]) * k / count;
        const Eigen::Vector2d p = geometry.Project(a + t * (b - a));
        const int x = static_cast<int>(std::lround(p.x())), y = static_cast<int>(std::lround(p.y()));
        if (x < 0 || y < 0 || x >= width_ || y >= height_) continue;
        std::vector<int>& list = edges_[static_cast<size_t>(y) * width_ + x];
        if (std::find(list.begin(), list.end(), s.edge) == list.end()) list.push_back(s.edge);
      }
    }
  }

  // Whether an edge other than `edge` passes within `radius` px of `p`.
  bool OtherEdgeNear(const Eigen::Vector2d& p, double radius, int edge) const {
    const int r = static_cast<int>(std::ceil(radius)) + 1;
    const int cx = static_cast<int>(std::lround(p.x())), cy = static_cast<int>(std::lround(p.y()));
    for (int y = cy - r; y <= cy + r; ++y) {
      for (int x = cx - r; x <= cx + r; ++x) {
        if (x < 0 || y < 0 || x >= width_ || y >= height_) continue;
        if ((Eigen::Vector2d(x, y) - p).norm() > radius + 0.75) continue;  // 0.75: a pixel's reach
        for (int e : edges_[static_cast<size_t>(y) * width_ + x]) {
          if (e != edge) return true;
        }
      }
    }
    return false;
  }

 private:
  int width_, height_;
  std::vector<std::vector<int>> edges_;
};

struct Probe {
  int frame = 0, edge = -1;
  int vertex = -1;         // the edge's wireframe vertex within kCornerReach px, or -1
  Eigen::Vector2d pixel;   // on the truth's edge
  Eigen::Vector2d normal;  // unit
  double offset = 0;       // px, rendered edge - truth edge along `normal`
};

struct CornerError {
  int frame = 0, vertex = -1;
  double error = 0;  // px, |rendered corner - the truth file's vertex pixel|
};

struct Agreement {
  std::vector<Probe> probes;
  std::vector<CornerError> corners;
};

// The probes of one frame, every ~3 px along each visible truth segment, and its corners: for a
// vertex with probes on two of its edges at least 30 deg apart, the rendered corner is where the
// two rendered edges meet, i.e. the projected vertex moved by d with n_i . d = (edge i's mean
// offset near the vertex).
void MeasureFrame(const cv::Mat& image, const Geometry& geometry, const Wireframe& wireframe,
                  const FrameTruth& frame, const ProbeSettings& settings, Agreement* agreement) {
  const Pose3 camera_T_world = frame.world_T_camera.Inverse();
  const EdgeMap map(geometry, camera_T_world, wireframe, frame.segments);
  // Per vertex, per edge: normal, summed offset, count.
  struct Side {
    Eigen::Vector2d normal;
    double offset = 0;
    int count = 0;
  };
  std::map<int, std::map<int, Side>> near_vertex;
  for (const VisibleSegment& s : frame.segments) {
    const WireEdge& edge = wireframe.edges[s.edge];
    const Eigen::Vector3d a = camera_T_world * wireframe.vertices[edge.vertex_a];
    const Eigen::Vector3d b = camera_T_world * wireframe.vertices[edge.vertex_b];
    const int count = static_cast<int>((geometry.End(s, 1) - geometry.End(s, 0)).norm() / 3);
    for (int k = 0; k < count; ++k) {
      const double t = s.t[0] + (s.t[1] - s.t[0]) * (k + 0.5) / count;
      const double dt = 1e-4 * (s.t[1] - s.t[0]);
      const Eigen::Vector2d p = geometry.Project(a + t * (b - a));
      const Eigen::Vector2d tangent =
          (geometry.Project(a + (t + dt) * (b - a)) - geometry.Project(a + (t - dt) * (b - a))).normalized();
      const Eigen::Vector2d normal(-tangent.y(), tangent.x());
      const double from[2] = {(p - geometry.End(s, 0)).norm(), (p - geometry.End(s, 1)).norm()};
      if (std::min(from[0], from[1]) < kEndMargin || !geometry.Inside(p, settings.Isolation())) continue;
      if (map.OtherEdgeNear(p, settings.Isolation(), s.edge)) continue;
      const std::optional<double> offset = EdgeOffset(image, p, normal, settings);
      if (!offset) continue;
      Probe probe;
      probe.frame = frame.index;
      probe.edge = s.edge;
      probe.pixel = p;
      probe.normal = normal;
      probe.offset = *offset;
      for (int i = 0; i < 2; ++i) {
        if (s.end[i] == SegmentEnd::kVertex && from[i] <= kCornerReach) {
          probe.vertex = i == 0 ? edge.vertex_a : edge.vertex_b;
          Side& side = near_vertex[probe.vertex][s.edge];
          side.normal = normal;
          side.offset += *offset;
          ++side.count;
        }
      }
      agreement->probes.push_back(probe);
    }
  }
  for (const VisibleVertex& v : frame.vertices) {
    const auto it = near_vertex.find(v.vertex);
    if (it == near_vertex.end()) continue;
    const Eigen::Vector2d projected = geometry.Project(camera_T_world * wireframe.vertices[v.vertex]);
    for (auto i = it->second.begin(); i != it->second.end(); ++i) {
      for (auto j = std::next(i); j != it->second.end(); ++j) {
        Eigen::Matrix2d N;
        N.row(0) = i->second.normal.transpose();
        N.row(1) = j->second.normal.transpose();
        if (std::abs(N.determinant()) < 0.5) continue;  // within 30 deg of parallel: ill-conditioned
        const Eigen::Vector2d d = N.inverse() * Eigen::Vector2d(i->second.offset / i->second.count,
                                                                j->second.offset / j->second.count);
        agreement->corners.push_back({frame.index, v.vertex, (projected + d - geometry.Vertex(v)).norm()});
      }
    }
  }
}

// Distance (px) from each occlusion end of a truth segment to the nearest other visible segment of
// its frame, in the undistorted image where all of them are straight: the end of a hidden edge lies
// on the occluder's contour, which the probes find where the image has it.
std::vector<double> OcclusionGaps(const FrameTruth& frame) {
  std::vector<double> gaps;
  for (const VisibleSegment& s : frame.segments) {
    for (int i = 0; i < 2; ++i) {
      if (s.end[i] != SegmentEnd::kOcclusion) continue;
      double gap = 1e9;
      for (const VisibleSegment& o : frame.segments) {
        if (o.edge == s.edge) continue;
        const Eigen::Vector2d d = o.pixel[1] - o.pixel[0];
        const double t = std::clamp((s.pixel[i] - o.pixel[0]).dot(d) / d.squaredNorm(), 0.0, 1.0);
        gap = std::min(gap, (o.pixel[0] + t * d - s.pixel[i]).norm());
      }
      gaps.push_back(gap);
    }
  }
  return gaps;
}

// What the stored images show, (with distortion) what they show once undistorted, and where the
// occlusion ends are.
struct Measured {
  Agreement stored, undistorted;
  std::vector<double> occlusion_gaps;
};

// Generates `options` without sensor noise and measures every frame's written image against its
// written truth.
Measured Measure(GeneratorOptions options, const std::string& name,
                 const ProbeSettings& settings = ProbeSettings()) {
  options.render.noise_sigma = 0;
  const std::string dir = testing::MakeScratchDir(name);
  const Status status = GenerateSequence(options, dir, /*overwrite=*/false);
  EXPECT_TRUE(status.ok()) << status.message();
  GroundTruth truth;
  const Status read = ReadGroundTruth(dir, &truth);
  EXPECT_TRUE(read.ok()) << read.message();
  Geometry stored, undistorted;
  stored.camera = undistorted.camera = options.camera.MakeCamera();
  undistorted.undistorted = true;
  const ImageUndistorter undistorter(stored.camera);
  Measured measured;
  for (const FrameTruth& frame : truth.frames) {
    char path[64];
    std::snprintf(path, sizeof(path), "/images/%06d.png", frame.index);
    const cv::Mat image = cv::imread(dir + path, cv::IMREAD_GRAYSCALE);
    EXPECT_FALSE(image.empty()) << dir << path;
    const std::vector<double> gaps = OcclusionGaps(frame);
    measured.occlusion_gaps.insert(measured.occlusion_gaps.end(), gaps.begin(), gaps.end());
    if (image.empty()) continue;
    MeasureFrame(image, stored, truth.wireframe, frame, settings, &measured.stored);
    if (stored.camera.HasDistortion()) {
      MeasureFrame(undistorter.Apply(image), undistorted, truth.wireframe, frame, settings,
                   &measured.undistorted);
    }
  }
  return measured;
}

// What a faithful rendering achieves. Defaults for the default renderer (3 x 3 samples per pixel,
// blur 0.7 px):
// - each probe within 0.45 px: the anti-aliasing places an edge to within half a sample (1/6 px),
//   the distorted image looks up the nearest canvas sample (another 1/6 px), and reading a blurred
//   8-bit profile bilinearly adds up to ~0.07 px. A wrong distortion direction or an inaccurate
//   undistortion moves edges by pixels near the border.
// - median |offset| below 0.08 px.
// - the least-squares shift common to all probes (n_i . d = offset_i) below 0.03 px: a
//   pixel-centre mistake of half a sample (1/6 px) or more shows here.
// - each corner within 1 px of the truth file's vertex, the median within 0.15 px.
struct Tolerances {
  double probe = 0.45, median = 0.08, shift = 0.03, corner = 1.0, corner_median = 0.15;
};

double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

void ExpectAgreement(const Agreement& agreement, size_t min_probes, size_t min_corners,
                     const Tolerances& tolerances = Tolerances()) {
  ASSERT_GE(agreement.probes.size(), min_probes);
  ASSERT_GE(agreement.corners.size(), min_corners);
  std::vector<double> edge_errors, corner_errors;
  Eigen::Matrix2d normal_equations = Eigen::Matrix2d::Zero();
  Eigen::Vector2d right_side = Eigen::Vector2d::Zero();
  int far_off = 0;
  for (const Probe& p : agreement.probes) {
    edge_errors.push_back(std::abs(p.offset));
    normal_equations += p.normal * p.normal.transpose();
    right_side += p.offset * p.normal;
    if (std::abs(p.offset) >= tolerances.probe && ++far_off <= 10) {
      ADD_FAILURE() << "frame " << p.frame << " edge " << p.edge << " at (" << p.pixel.transpose()
                    << "): the rendered edge is " << p.offset << " px off the truth";
    }
  }
  EXPECT_EQ(far_off, 0) << "probes " << tolerances.probe << " px or more off, of " << agreement.probes.size();
  const Eigen::Vector2d shift = normal_equations.ldlt().solve(right_side);
  EXPECT_LT(shift.norm(), tolerances.shift) << "common shift " << shift.transpose();
  EXPECT_LT(Median(edge_errors), tolerances.median);
  int far_corners = 0;
  for (const CornerError& c : agreement.corners) {
    corner_errors.push_back(c.error);
    if (c.error >= tolerances.corner && ++far_corners <= 10) {
      ADD_FAILURE() << "frame " << c.frame << " vertex " << c.vertex << ": the rendered corner is " << c.error
                    << " px from the truth";
    }
  }
  EXPECT_EQ(far_corners, 0) << "corners " << tolerances.corner << " px or more off, of "
                            << agreement.corners.size();
  EXPECT_LT(Median(corner_errors), tolerances.corner_median);
  std::printf(
      "  %zu edge probes: median |offset| %.3f px, max %.3f px, common shift (%.4f, %.4f) px; %zu corners: "
      "median %.3f px, max %.3f px\n",
      edge_errors.size(), Median(edge_errors), *std::max_element(edge_errors.begin(), edge_errors.end()),
      shift.x(), shift.y(), corner_errors.size(), Median(corner_errors),
      *std::max_element(corner_errors.begin(), corner_errors.end()));
}

// Occlusion ends: the visibility test hides a point when a nearer face is in any of the four canvas
// samples around it, so an end lies up to one sample (1/3 px) short of the occluder's contour,
// 1/6 px on average. Measured: median 0.18-0.19 px, 99 % 0.37 px; at most 0.97 px, at a box top
// seen almost edge-on (0.5 px tall), where the samples around its far edge reach the near side.
void ExpectOcclusionEndsOnContours(std::vector<double> gaps, size_t min_count) {
  ASSERT_GE(gaps.size(), min_count);
  std::sort(gaps.begin(), gaps.end());
  EXPECT_LT(gaps[gaps.size() / 2], 0.25);
  EXPECT_LT(gaps[gaps.size() * 99 / 100], 0.45);
  EXPECT_LT(gaps.back(), 1.5);
  std::printf("  %zu occlusion ends: median %.3f px, 99 %% %.3f px, max %.3f px from another truth edge\n",
              gaps.size(), gaps[gaps.size() / 2], gaps[gaps.size() * 99 / 100], gaps.back());
}

// The sequence scripts/benchmark_junctions.sh calls corridor-distorted (StandardSequences in
// benchmarks/junctions/benchmark_junctions.cc), where vertex 463 was seen drawn "4-5 px higher" than its
// truth in frames 17-28.
GeneratorOptions CorridorDistorted() {
  GeneratorOptions options;
  options.scene.type = SceneType::kCorridor;
  options.trajectory.type = TrajectoryType::kTurns;
  options.trajectory.num_frames = 30;
  options.camera.distortion = {-0.25, 0.07, 0.0005, -0.0005, 0};
  options.seed = 13;
  return options;
}

// ExpectAgreement on the stored image and on the undistorted one.
void ExpectBothImagesAgree(const Measured& measured, size_t min_probes, size_t min_corners,
                           const Tolerances& tolerances = Tolerances()) {
  {
    SCOPED_TRACE("stored image");
    ExpectAgreement(measured.stored, min_probes, min_corners, tolerances);
  }
  {
    SCOPED_TRACE("undistorted image");
    ExpectAgreement(measured.undistorted, min_probes, min_corners, tolerances);
  }
}

// Both the stored image against the truth's distorted pixels (u_dist v_dist), and the junction
// benchmark's view: that image undistorted by ImageUndistorter (OpenCV's remap) against the
// truth's undistorted pixels (u v).
TEST(RenderedTruthTest, CorridorDistortedStoredAndUndistortedImages) {
  const Measured measured = Measure(CorridorDistorted(), "rendered_truth_distorted");
  ExpectBothImagesAgree(measured, 5000, 300);
  ExpectOcclusionEndsOnContours(measured.occlusion_gaps, 1000);
}

// Sharp rendering (6 x 6 samples, no blur): steps are 1 px wide, so the profile needs 2.5 px each
// way and a probe 3.5 px of clearance from other edges (5 px with the blur), which lets in more
// probes between close edges (35 k instead of 28 k). An edge is placed to half a sample (1/12 px),
// twice over with distortion, and bilinear reading of an unblurred step errs by up to 1/8 px.
// Measured: median 0.052 px, max 0.24 px; corners median 0.07 px, max 0.29 px. (The two top edges
// of the report's cabinet, 2.8 px apart across in frame 22, are still too close to probe.)
TEST(RenderedTruthTest, CorridorDistortedSharpRenderingNearbyEdges) {
  GeneratorOptions options = CorridorDistorted();
  options.render.supersampling = 6;
  options.render.blur_sigma = 0;
  ProbeSettings settings;
  settings.reach = 2.5;
  settings.plateau = 1.75;
  Tolerances tolerances;
  tolerances.probe = 0.3;
  tolerances.median = 0.06;
  tolerances.shift = 0.02;
  tolerances.corner = 0.6;
  tolerances.corner_median = 0.1;
  ExpectAgreement(Measure(options, "rendered_truth_sharp", settings).stored, 10000, 300, tolerances);
}

// The junction benchmark's undistorted corridor, for the pixel-centre convention without the
// distortion's resampling.
TEST(RenderedTruthTest, CorridorWithoutDistortion) {
  GeneratorOptions options;
  options.scene.type = SceneType::kCorridor;
  options.trajectory.num_frames = 30;
  options.seed = 11;
  const Measured measured = Measure(options, "rendered_truth_plain");
  ExpectAgreement(measured.stored, 5000, 300);
  ExpectOcclusionEndsOnContours(measured.occlusion_gaps, 1000);
}

// Strong tangential terms (8x the benchmark's) and k3, in a room: p1 and p2 swapped, or their
// signs, move edges by ~1 px near the image corners.
TEST(RenderedTruthTest, RoomWithStrongTangentialDistortion) {
  GeneratorOptions options;
  options.scene.type = SceneType::kRoom;
  options.trajectory.type = TrajectoryType::kLoop;
  options.trajectory.num_frames = 8;
  options.camera.width = 320;
  options.camera.height = 240;
  options.camera.fx = options.camera.fy = 225;
  options.camera.distortion = {-0.3, 0.1, 0.004, -0.003, -0.01};
  options.seed = 5;
  const Measured measured = Measure(options, "rendered_truth_room");
  // 8 frames of one room see the same few long edges again and again, so their anti-aliasing
  // errors (up to 1/6 px each) do not average out as over 30 corridor frames: measured common
  // shifts 0.013 px (stored) and 0.030 px (undistorted; OpenCV's remap also rounds its map to
  // 1/32 px). Still well below a half-sample mistake (0.17 px).
  Tolerances tolerances;
  tolerances.shift = 0.06;
  ExpectBothImagesAgree(measured, 500, 20, tolerances);
}

// make_sequence --lens equidistant (issue 21): a 150-degree diagonal fisheye with non-zero
// Kannala-Brandt coefficients, in a room. The stored image must show every truth edge where
// cv::fisheye puts it, and the undistorted image (cv::fisheye's remap maps) where K does, to the
// same tolerances as the radial-tangential lenses: a mistake in theta's polynomial moves edges by
// pixels near the border. Measured: stored median 0.042 px, max 0.29 px, corners max 0.41 px;
// undistorted median 0.059 px, max 0.32 px.
TEST(RenderedTruthTest, RoomThroughAnEquidistantFisheye) {
  GeneratorOptions options;
  options.scene.type = SceneType::kRoom;
  options.trajectory.type = TrajectoryType::kLoop;
  options.trajectory.num_frames = 8;
  options.camera.width = 320;
  options.camera.height = 240;
  options.camera.model = DistortionModel::kEquidistant;
  options.camera.distortion = {0.03, -0.01, 0.004, -0.0006, 0};
  options.camera.fx = options.camera.fy = options.camera.EquidistantFocalForDiagonal(150 * M_PI / 180);
  options.seed = 5;
  const Measured measured = Measure(options, "rendered_truth_fisheye");
  Tolerances tolerances;
  tolerances.shift = 0.06;
  ExpectBothImagesAgree(measured, 500, 20, tolerances);
}

}  // namespace
}  // namespace sfm
