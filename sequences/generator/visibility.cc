#include "sequences/generator/visibility.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <glog/logging.h>

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

enum class Seen { kVisible, kOutside, kOccluded };

class View {
 public:
  View(const Scene& scene, const Camera& camera, const Pose3& world_T_camera, const Canvas& canvas,
       const VisibilityOptions& options)
      : camera_(camera), canvas_(canvas), options_(options) {
    const Pose3 camera_T_world = world_T_camera.Inverse();
    R_ = camera_T_world.RotationMatrix();
    t_ = camera_T_world.translation;
    normal_.reserve(scene.faces.size());
    offset_.reserve(scene.faces.size());
    for (const Face& face : scene.faces) {
      const Eigen::Vector3d n = R_ * face.normal;
      normal_.push_back(n);
      offset_.push_back(n.dot(R_ * face.vertices.front() + t_));
    }
  }

  Eigen::Vector3d ToCamera(const Eigen::Vector3d& world) const { return R_ * world + t_; }
  Eigen::Vector2d Undistorted(const Eigen::Vector3d& pc) const {
    return {camera_.fx * pc.x() / pc.z() + camera_.cx, camera_.fy * pc.y() / pc.z() + camera_.cy};
  }
  Eigen::Vector2d Distorted(const Eigen::Vector2d& undistorted) const {
    return camera_.HasDistortion() ? camera_.DistortPixel(undistorted) : undistorted;
  }
  bool OnCanvas(const Eigen::Vector2d& undistorted) const {
    const Eigen::Vector2d s = canvas_.ToSample(undistorted);
    return s.x() >= 0 && s.y() >= 0 && s.x() <= canvas_.width - 1 && s.y() <= canvas_.height - 1;
  }
  // Undistorted pixel range the canvas covers.
  Eigen::Vector2d CanvasMin() const { return {canvas_.origin_x, canvas_.origin_y}; }
  Eigen::Vector2d CanvasMax() const {
    return {canvas_.origin_x + (canvas_.width - 1.0) / canvas_.scale,
            canvas_.origin_y + (canvas_.height - 1.0) / canvas_.scale};
  }

  Seen Classify(const Eigen::Vector3d& pc) const {
    if (pc.z() < options_.near) return Seen::kOutside;
    const Eigen::Vector2d q = Undistorted(pc);
    if (!OnCanvas(q)) return Seen::kOutside;
    const Eigen::Vector2d d = Distorted(q);
    if (d.x() < -0.5 || d.y() < -0.5 || d.x() > camera_.width - 0.5 || d.y() > camera_.height - 0.5) {
      return Seen::kOutside;
    }
    const Eigen::Vector2d s = canvas_.ToSample(q);
    const int i0 = static_cast<int>(std::floor(s.x())), j0 = static_cast<int>(std::floor(s.y()));
    const Eigen::Vector3d ray(pc.x() / pc.z(), pc.y() / pc.z(), 1.0);
    const double limit = pc.z() * (1 - options_.depth_tolerance);
    int tested[4] = {-1, -1, -1, -1};
    for (int k = 0; k < 4; ++k) {
      const int f = canvas_.FaceAt(i0 + (k & 1), j0 + (k >> 1));
      if (f < 0 || std::find(tested, tested + k, f) != tested + k) continue;
      tested[k] = f;
      const double denominator = normal_[f].dot(ray);
      if (std::abs(denominator) < 1e-12) continue;
      const double z = offset_[f] / denominator;  // depth where the ray meets the face's plane
      if (z > 0 && z < limit) return Seen::kOccluded;
    }
    return Seen::kVisible;
  }

 private:
  const Camera& camera_;
  const Canvas& canvas_;
  const VisibilityOptions& options_;
  Eigen::Matrix3d R_;
  Eigen::Vector3d t_;
  std::vector<Eigen::Vector3d> normal_;
  std::vector<double> offset_;
};

// Liang-Barsky: the part [s0, s1] of p + s (q - p), s in [0, 1], inside the box lo..hi.
bool ClipToBox(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& lo,
               const Eigen::Vector2d& hi, double* s0, double* s1) {
  *s0 = 0;
  *s1 = 1;
  const Eigen::Vector2d d = q - p;
  for (int axis = 0; axis < 2; ++axis) {
    const double bounds[2] = {lo[axis], hi[axis]};
    if (std::abs(d[axis]) < 1e-15) {
      if (p[axis] < bounds[0] || p[axis] > bounds[1]) return false;
      continue;
    }
    double a = (bounds[0] - p[axis]) / d[axis], b = (bounds[1] - p[axis]) / d[axis];
    if (a > b) std::swap(a, b);
    *s0 = std::max(*s0, a);
    *s1 = std::min(*s1, b);
  }
  return *s0 <= *s1;
}

std::string JunctionType(std::vector<Eigen::Vector2d> directions, double collinear_tolerance) {
  const int n = static_cast<int>(directions.size());
  if (n < 2) return "-";
  if (n == 4) return "X";
  if (n > 4) return "N";
  std::vector<double> angles;
  for (const Eigen::Vector2d& d : directions) angles.push_back(std::atan2(d.y(), d.x()));
  std::sort(angles.begin(), angles.end());
  auto straight = [&](double a, double b) {
    double difference = std::abs(a - b);
    if (difference > kPi) difference = 2 * kPi - difference;
    return std::abs(difference - kPi) < collinear_tolerance;
  };
  if (n == 2) return straight(angles[0], angles[1]) ? "-" : "L";
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (straight(angles[i], angles[j])) return "T";
    }
  }
  double max_gap = 0;
  for (int i = 0; i < 3; ++i) {
    const double gap = i < 2 ? angles[i + 1] - angles[i] : angles[0] + 2 * kPi - angles[2];
    max_gap = std::max(max_gap, gap);
  }
  return max_gap > kPi ? "ARROW" : "Y";
}

}  // namespace

void ComputeFrameTruth(const Scene& scene, const Wireframe& wireframe, const Camera& camera,
                       const Pose3& world_T_camera, const Canvas& canvas, const VisibilityOptions& options,
                       FrameTruth* truth) {
  CHECK(truth != nullptr);
  CHECK_GT(options.sample_spacing, 0);
  const View view(scene, camera, world_T_camera, canvas, options);
  truth->world_T_camera = world_T_camera;
  truth->vertices.clear();
  truth->segments.clear();
  // Directions (undistorted image) of the visible edges leaving each vertex.
  std::map<int, std::vector<Eigen::Vector2d>> directions;

  for (int e = 0; e < static_cast<int>(wireframe.edges.size()); ++e) {
    const WireEdge& edge = wireframe.edges[e];
    const Eigen::Vector3d a = view.ToCamera(wireframe.vertices[edge.vertex_a]);
    const Eigen::Vector3d b = view.ToCamera(wireframe.vertices[edge.vertex_b]);
    // Part in front of the near plane, t in [t0, t1].
    double t0 = 0, t1 = 1;
    if (a.z() < options.near && b.z() < options.near) continue;
    if (a.z() < options.near) t0 = (options.near - a.z()) / (b.z() - a.z());
    if (b.z() < options.near) t1 = (options.near - a.z()) / (b.z() - a.z());
    const Eigen::Vector3d a_near = a + t0 * (b - a), b_near = a + t1 * (b - a);
    const double za = std::max(a_near.z(), options.near), zb = std::max(b_near.z(), options.near);
    const Eigen::Vector2d pa = view.Undistorted({a_near.x(), a_near.y(), za});
    const Eigen::Vector2d pb = view.Undistorted({b_near.x(), b_near.y(), zb});
    // Image parameter s (linear in the undistorted image) -> edge parameter t (perspective).
    auto t_of = [&](double s) { return t0 + (t1 - t0) * (s * za) / ((1 - s) * zb + s * za); };
    auto point = [&](double s) { return Eigen::Vector3d(a + t_of(s) * (b - a)); };
    double s_lo = 0, s_hi = 1;
    if (!ClipToBox(pa, pb, view.CanvasMin(), view.CanvasMax(), &s_lo, &s_hi)) continue;
    const double length = (pb - pa).norm() * (s_hi - s_lo);
    const int count = std::max(2, static_cast<int>(std::ceil(length / options.sample_spacing)) + 1);
    std::vector<double> s(count);
    std::vector<Seen> seen(count);
    for (int k = 0; k < count; ++k) {
      s[k] = k + 1 == count ? s_hi : s_lo + (s_hi - s_lo) * k / (count - 1);
      seen[k] = view.Classify(point(s[k]));
    }
    // Bisection between a hidden sample and a visible one: the visible end, and why it ends.
    auto refine = [&](double hidden, double visible, SegmentEnd* why) {
      Seen hidden_seen = Seen::kOutside;
      for (int step = 0; step < options.bisection_steps; ++step) {
        const double mid = 0.5 * (hidden + visible);
        const Seen m = view.Classify(point(mid));
        if (m == Seen::kVisible) {
          visible = mid;
        } else {
          hidden = mid;
          hidden_seen = m;
        }
      }
      if (hidden_seen == Seen::kOutside) hidden_seen = view.Classify(point(hidden));
      *why = hidden_seen == Seen::kOccluded ? SegmentEnd::kOcclusion : SegmentEnd::kBorder;
      return visible;
    };
    for (int k = 0; k < count;) {
      if (seen[k] != Seen::kVisible) {
        ++k;
        continue;
      }
      int last = k;
      while (last + 1 < count && seen[last + 1] == Seen::kVisible) ++last;
      VisibleSegment segment;
      segment.edge = e;
      double s_start = s[k], s_end = s[last];
      if (k == 0) {
        segment.end[0] = (t0 == 0 && s_lo == 0) ? SegmentEnd::kVertex : SegmentEnd::kBorder;
      } else {
        s_start = refine(s[k - 1], s[k], &segment.end[0]);
      }
      if (last == count - 1) {
        segment.end[1] = (t1 == 1 && s_hi == 1) ? SegmentEnd::kVertex : SegmentEnd::kBorder;
      } else {
        s_end = refine(s[last + 1], s[last], &segment.end[1]);
      }
      k = last + 1;
      const double ends[2] = {s_start, s_end};
      for (int i = 0; i < 2; ++i) {
        // The ends that are the edge's own vertices are exactly them.
        segment.t[i] = segment.end[i] == SegmentEnd::kVertex ? i : t_of(ends[i]);
        const Eigen::Vector3d pc = segment.t[i] == 0 ? a : segment.t[i] == 1 ? b : a + segment.t[i] * (b - a);
        segment.pixel[i] = view.Undistorted(pc);
        segment.pixel_distorted[i] = view.Distorted(segment.pixel[i]);
      }
      if ((segment.pixel[1] - segment.pixel[0]).norm() < options.min_segment_length) continue;
      if (segment.end[0] == SegmentEnd::kVertex) {
        directions[edge.vertex_a].push_back(segment.pixel[1] - segment.pixel[0]);
      }
      if (segment.end[1] == SegmentEnd::kVertex) {
        directions[edge.vertex_b].push_back(segment.pixel[0] - segment.pixel[1]);
      }
      truth->segments.push_back(segment);
    }
  }

  for (int v = 0; v < static_cast<int>(wireframe.vertices.size()); ++v) {
    const Eigen::Vector3d pc = view.ToCamera(wireframe.vertices[v]);
    if (view.Classify(pc) != Seen::kVisible) continue;
    VisibleVertex vertex;
    vertex.vertex = v;
    vertex.pixel = camera.ProjectUndistorted(pc);
    vertex.pixel_distorted = view.Distorted(vertex.pixel);
    vertex.depth = pc.z();
    const auto it = directions.find(v);
    if (it != directions.end()) {
      vertex.degree = static_cast<int>(it->second.size());
      vertex.type = JunctionType(it->second, options.collinear_tolerance);
    }
    truth->vertices.push_back(vertex);
  }
}

}  // namespace sfm
