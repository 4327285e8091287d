#include "backend/triangulation/point_triangulation.h"

#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

double SumOfSquaredErrors(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                          const Eigen::Vector3d& point) {
  double sum = 0;
  for (double error : ReprojectionErrors(K, views, point)) sum += error * error;
  return sum;
}

bool InFrontOfAll(const std::vector<PointView>& views, const Eigen::Vector3d& point, double min_depth = 0) {
  for (const PointView& view : views) {
    const double z = (view.world_T_camera.Inverse() * point).z();
    if (!(z > 0 && z >= min_depth)) return false;
  }
  return true;
}

}  // namespace

const char* PointStatusName(PointStatus status) {
  switch (status) {
    case PointStatus::kOk:
      return "ok";
    case PointStatus::kTooFewViews:
      return "too_few_views";
    case PointStatus::kLowParallax:
      return "low_parallax";
    case PointStatus::kBehindCamera:
      return "behind_camera";
    case PointStatus::kLargeReprojectionError:
      return "large_reprojection_error";
    case PointStatus::kTooClose:
      return "too_close";
  }
  return "unknown";
}

double MaxRayAngle(const Eigen::Matrix3d& K, const std::vector<PointView>& views) {
  const Eigen::Matrix3d K_inverse = K.inverse();
  std::vector<Eigen::Vector3d> rays;
  for (const PointView& view : views) {
    rays.push_back(view.world_T_camera.rotation * (K_inverse * view.pixel.homogeneous()));
  }
  double largest = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    for (size_t j = i + 1; j < rays.size(); ++j) {
      largest = std::max(largest, std::atan2(rays[i].cross(rays[j]).norm(), rays[i].dot(rays[j])));
    }
  }
  return largest;
}

Eigen::Vector4d TriangulateDlt(const Eigen::Matrix3d& K, const std::vector<PointView>& views) {
  CHECK_GE(views.size(), 2u) << "triangulation needs two views";
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const PointView& view : views) centre += view.world_T_camera.translation;
  centre /= static_cast<double>(views.size());

  const Eigen::Matrix3d K_inverse = K.inverse();
  Eigen::MatrixXd A(2 * views.size(), 4);
  for (size_t i = 0; i < views.size(); ++i) {
    // camera_T_world for the centred world X' = X - centre: p_camera = R X' + (R centre + t).
    const Pose3 camera_T_world = views[i].world_T_camera.Inverse();
    Eigen::Matrix<double, 3, 4> P;
    P.leftCols<3>() = camera_T_world.RotationMatrix();
    P.col(3) = camera_T_world * centre;
    const Eigen::Vector3d x = K_inverse * views[i].pixel.homogeneous();
    A.row(2 * i) = x.x() / x.z() * P.row(2) - P.row(0);
    A.row(2 * i + 1) = x.y() / x.z() * P.row(2) - P.row(1);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d centred = svd.matrixV().col(3);
  Eigen::Vector4d point;
  point << centred.head<3>() + centred.w() * centre, centred.w();
  return point;
}

std::vector<double> ReprojectionErrors(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                                       const Eigen::Vector3d& point) {
  std::vector<double> errors;
  for (const PointView& view : views) {
    const Eigen::Vector3d p_camera = view.world_T_camera.Inverse() * point;
    errors.push_back(p_camera.z() > 0 ? ((K * p_camera).hnormalized() - view.pixel).norm()
                                      : std::numeric_limits<double>::infinity());
  }
  return errors;
}

Eigen::Vector3d RefinePoint(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                            const Eigen::Vector3d& point, int iterations) {
  CHECK(InFrontOfAll(views, point)) << "refinement needs a point in front of every camera";
  Eigen::Vector3d x = point;
  double cost = SumOfSquaredErrors(K, views, x);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (const PointView& view : views) {
      const Pose3 camera_T_world = view.world_T_camera.Inverse();
      const Eigen::Vector3d p = camera_T_world * x;
      // d pixel / d p_camera = K(0:2, 0:2) * [1/z 0 -x/z^2; 0 1/z -y/z^2]; then * R for the world.
      Eigen::Matrix<double, 2, 3> d_normalised;
      d_normalised << 1 / p.z(), 0, -p.x() / (p.z() * p.z()), 0, 1 / p.z(), -p.y() / (p.z() * p.z());
      const Eigen::Matrix<double, 2, 3> J =
          K.topLeftCorner<2, 2>() * d_normalised * camera_T_world.RotationMatrix();
      const Eigen::Vector2d r = (K * p).hnormalized() - view.pixel;
      H += J.transpose() * J;
      g += J.transpose() * r;
    }
    const Eigen::Vector3d candidate = x - H.ldlt().solve(g);
    const double candidate_cost = SumOfSquaredErrors(K, views, candidate);
    if (!(candidate_cost < cost)) break;
    x = candidate;
    cost = candidate_cost;
  }
  return x;
}

PointStatus TriangulatePoint(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                             const PointTriangulationOptions& options, Eigen::Vector3d* point) {
  CHECK(options.Check().ok()) << options.Check().message();
  if (views.size() < 2) return PointStatus::kTooFewViews;
  if (!(MaxRayAngle(K, views) > options.min_parallax_deg * kPi / 180)) return PointStatus::kLowParallax;
  const Eigen::Vector4d homogeneous = TriangulateDlt(K, views);
  // Rays that pass the parallax test meet at a finite point unless the observations contradict
  // each other so much that the best fit is at infinity: then no depth is determined either.
  if (!(std::abs(homogeneous.w()) > 1e-12 * homogeneous.head<3>().norm())) return PointStatus::kLowParallax;
  const Eigen::Vector3d linear = homogeneous.hnormalized();
  if (!InFrontOfAll(views, linear)) return PointStatus::kBehindCamera;
  const Eigen::Vector3d refined = RefinePoint(K, views, linear, options.refinement_iterations);
  const std::vector<double> errors = ReprojectionErrors(K, views, refined);
  if (!(*std::max_element(errors.begin(), errors.end()) < options.max_reprojection_error_px)) {
    return PointStatus::kLargeReprojectionError;
  }
  if (!InFrontOfAll(views, refined, options.min_depth_m)) return PointStatus::kTooClose;
  *point = refined;
  return PointStatus::kOk;
}

}  // namespace sfm
