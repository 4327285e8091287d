#include "tests/bundle_adjustment/synthetic_room.h"

#include <glog/logging.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>

#include "backend/bundle_adjustment/bundle_adjuster.h"
#include "backend/triangulation/reconstruction.h"

namespace sfm::testing {
namespace {

constexpr double kMinDepth = 0.1;             // m, in front of the camera
constexpr double kMinSegmentLengthPx = 30.0;  // px, shorter visible segments are not observed

Pose3 Yaw(double yaw, const Eigen::Vector3d& translation) {
  return Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), translation);
}

// Adds the 4 corners (in order) and the 4 edges of a rectangle.
void AddRectangle(const std::vector<Eigen::Vector3d>& corners, Scene* scene) {
  const int first = static_cast<int>(scene->points.size());
  for (const Eigen::Vector3d& corner : corners) scene->points.push_back(corner);
  for (int k = 0; k < 4; ++k) {
    scene->segments.push_back({corners[k], corners[(k + 1) % 4], first + k});
  }
}

// The rectangle [u0, u1] x [z0, z1] on the wall x = x_wall (u along y) or y = y_wall (u along x).
std::vector<Eigen::Vector3d> WallRectangle(bool wall_at_x, double wall, double u0, double u1, double z0,
                                           double z1) {
  auto at = [&](double u, double z) {
    return wall_at_x ? Eigen::Vector3d(wall, u, z) : Eigen::Vector3d(u, wall, z);
  };
  return {at(u0, z0), at(u1, z0), at(u1, z1), at(u0, z1)};
}

Eigen::Matrix<double, 3, 4> ProjectionMatrix(const Calibration& calibration, const Pose3& world_T_base) {
  const Pose3 camera_T_world = (world_T_base * calibration.base_T_camera).Inverse();
  return calibration.camera.K() * camera_T_world.Matrix3x4();
}

// Liang-Barsky clipping of the segment a-b to [0, width-1] x [0, height-1]; false when nothing is left.
bool ClipToImage(int width, int height, Eigen::Vector2d* a, Eigen::Vector2d* b) {
  const Eigen::Vector2d d = *b - *a;
  double t0 = 0, t1 = 1;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a->x(), width - 1 - a->x(), a->y(), height - 1 - a->y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0) {
      if (q[k] < 0) return false;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  if (t0 >= t1) return false;
  *b = *a + t1 * d;
  *a += t0 * d;
  return true;
}

}  // namespace

Scene BoxRoom() {
  Scene scene;
  const double X = 8, Y = 6, Z = 3;
  for (int k = 0; k < 8; ++k) scene.points.emplace_back((k & 1) * X, ((k >> 1) & 1) * Y, ((k >> 2) & 1) * Z);
  // Corner k has bits (x, y, z); an edge joins two corners that differ in one bit.
  for (int k = 0; k < 8; ++k) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (!(k & bit)) scene.segments.push_back({scene.points[k], scene.points[k | bit], k});
    }
  }
  AddRectangle(WallRectangle(false, 0.0, 1.5, 3.0, 0.9, 1.9), &scene);  // south wall
  AddRectangle(WallRectangle(false, 0.0, 4.8, 6.0, 1.2, 2.4), &scene);
  AddRectangle(WallRectangle(false, Y, 1.2, 2.4, 1.0, 2.2), &scene);  // north wall
  AddRectangle(WallRectangle(false, Y, 4.0, 6.5, 0.8, 1.6), &scene);
  AddRectangle(WallRectangle(true, 0.0, 1.5, 2.7, 1.0, 2.0), &scene);  // west wall
  AddRectangle(WallRectangle(true, 0.0, 3.6, 4.6, 1.4, 2.6), &scene);
  AddRectangle(WallRectangle(true, X, 1.0, 2.5, 0.6, 1.8), &scene);  // east wall
  AddRectangle(WallRectangle(true, X, 3.5, 5.0, 1.3, 2.3), &scene);
  return scene;
}

Scene BoxRoomWithRugs(double floor_z) {
  Scene scene = BoxRoom();
  auto rug = [](double x0, double x1, double y0, double y1) {
    return std::vector<Eigen::Vector3d>{{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
  };
  AddRectangle(rug(3.0, 4.5, 0.4, 1.0), &scene);  // between the loop and the south wall
  AddRectangle(rug(3.5, 5.0, 5.0, 5.6), &scene);  // north
  AddRectangle(rug(0.4, 1.0, 2.0, 3.5), &scene);  // west
  AddRectangle(rug(7.0, 7.6, 2.5, 4.0), &scene);  // east
  const Eigen::Vector3d shift(0, 0, floor_z);
  for (Eigen::Vector3d& point : scene.points) point += shift;
  for (Scene::Segment& segment : scene.segments) {
    segment.a += shift;
    segment.b += shift;
  }
  return scene;
}

Calibration RobotCalibration(double forward, double height) {
  Calibration calibration;
  Camera& camera = calibration.camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 450;
  camera.cx = (camera.width - 1) / 2.0;
  camera.cy = (camera.height - 1) / 2.0;
  Eigen::Matrix3d base_R_camera;
  base_R_camera.col(0) = -Eigen::Vector3d::UnitY();  // camera x = -base y
  base_R_camera.col(1) = -Eigen::Vector3d::UnitZ();  // camera y = -base z
  base_R_camera.col(2) = Eigen::Vector3d::UnitX();   // camera z = base x
  calibration.base_T_camera = Pose3(base_R_camera, Eigen::Vector3d(forward, 0, height));
  return calibration;
}

std::vector<Pose3> LoopTrajectory(int frames) {
  std::vector<Pose3> poses;
  const double a = 2.2, b = 1.3;
  for (int i = 0; i < frames; ++i) {
    const double theta = 2 * M_PI * i / frames;
    const double yaw = std::atan2(b * std::cos(theta), -a * std::sin(theta));
    poses.push_back(Yaw(yaw, Eigen::Vector3d(4 + a * std::cos(theta), 3 + b * std::sin(theta), 0)));
  }
  return poses;
}

std::vector<Pose3> StraightTrajectory(int frames, const Eigen::Vector2d& start, double step) {
  std::vector<Pose3> poses;
  for (int i = 0; i < frames; ++i)
    poses.push_back(Yaw(0, Eigen::Vector3d(start.x() + i * step, start.y(), 0)));
  return poses;
}

std::vector<Pose3> MakeOdometry(const std::vector<Pose3>& world_T_base_true, double scale_error,
                                double heading_drift_rad, double heading_noise_rad, std::uint32_t seed) {
  std::vector<Pose3> odometry;
  if (world_T_base_true.empty()) return odometry;
  std::mt19937 random(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  odometry.push_back(world_T_base_true.front());
  for (size_t i = 1; i < world_T_base_true.size(); ++i) {
    const Pose3 motion = world_T_base_true[i - 1].Inverse() * world_T_base_true[i];
    const double yaw = heading_drift_rad + heading_noise_rad * gaussian(random);
    const Pose3 noisy(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * motion.rotation,
                      (1 + scale_error) * motion.translation);
    odometry.push_back(odometry.back() * noisy);
  }
  return odometry;
}

Observed Observe(const Scene& scene, const Calibration& calibration,
                 const std::vector<Pose3>& world_T_base_true, const std::vector<Pose3>& world_T_base_odometry,
                 double pixel_noise_px, std::uint32_t seed) {
  CHECK_EQ(world_T_base_true.size(), world_T_base_odometry.size());
  std::mt19937 random(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  auto noise = [&]() {
    const double x = pixel_noise_px * gaussian(random);
    const double y = pixel_noise_px * gaussian(random);
    return Eigen::Vector2d(x, y);
  };
  const Camera& camera = calibration.camera;
  const Eigen::Matrix3d K = camera.K();
  auto inside = [&](const Eigen::Vector2d& p) {
    return p.x() >= 0 && p.y() >= 0 && p.x() <= camera.width - 1 && p.y() <= camera.height - 1;
  };
  const int frames = static_cast<int>(world_T_base_true.size());
  std::vector<Pose3> camera_T_world(frames);
  std::vector<Eigen::Matrix<double, 3, 4>> odometry_P(frames);
  for (int f = 0; f < frames; ++f) {
    camera_T_world[f] = (world_T_base_true[f] * calibration.base_T_camera).Inverse();
    odometry_P[f] = ProjectionMatrix(calibration, world_T_base_odometry[f]);
  }

  Observed observed;
  std::map<int, int> landmark_of_point;
  for (size_t i = 0; i < scene.points.size(); ++i) {
    PointLandmark landmark;
    landmark.track_id = static_cast<int>(i);
    for (int f = 0; f < frames; ++f) {
      const Eigen::Vector3d p = camera_T_world[f] * scene.points[i];
      if (p.z() < kMinDepth) continue;
      const Eigen::Vector2d pixel = (K * p).hnormalized();
      if (!inside(pixel)) continue;
      landmark.observations.push_back({f, static_cast<int>(i), pixel + noise()});
    }
    if (landmark.observations.size() < 2) continue;
    // Linear triangulation (Hartley & Zisserman section 12.2) from the odometry poses.
    Eigen::MatrixXd A(2 * landmark.observations.size(), 4);
    for (size_t k = 0; k < landmark.observations.size(); ++k) {
      const PointObservation& observation = landmark.observations[k];
      const Eigen::Matrix<double, 3, 4>& P = odometry_P[observation.frame];
      A.row(2 * k) = observation.pixel.x() * P.row(2) - P.row(0);
      A.row(2 * k + 1) = observation.pixel.y() * P.row(2) - P.row(1);
    }
    const Eigen::Vector4d X = Eigen::JacobiSVD<Eigen::MatrixXd>(A, Eigen::ComputeFullV).matrixV().col(3);
    landmark.position = X.hnormalized();
    landmark_of_point[static_cast<int>(i)] = static_cast<int>(observed.landmarks.points.size());
    observed.landmarks.points.push_back(landmark);
    observed.true_points.push_back(scene.points[i]);
  }

  for (const Scene::Segment& segment : scene.segments) {
    LineLandmark landmark;
    for (int f = 0; f < frames; ++f) {
      Eigen::Vector3d a = camera_T_world[f] * segment.a, b = camera_T_world[f] * segment.b;
      if (a.z() < kMinDepth && b.z() < kMinDepth) continue;
      // Clip to the plane z = kMinDepth.
      if (a.z() < kMinDepth) a = b + (a - b) * (b.z() - kMinDepth) / (b.z() - a.z());
      if (b.z() < kMinDepth) b = a + (b - a) * (a.z() - kMinDepth) / (a.z() - b.z());
      Eigen::Vector2d a_px = (K * a).hnormalized(), b_px = (K * b).hnormalized();
      if (!ClipToImage(camera.width, camera.height, &a_px, &b_px) ||
          (b_px - a_px).norm() < kMinSegmentLengthPx) {
        continue;
      }
      LineObservation observation;
      observation.frame = f;
      observation.junction = segment.point_at_a;
      observation.segment = 0;
      observation.p0 = a_px + noise();
      observation.p1 = b_px + noise();
      landmark.observations.push_back(observation);
    }
    if (landmark.observations.size() < 2) continue;
    // The line common to the back-projected planes P^T l of its views, least squares (the two
    // right singular vectors of the smallest singular values span its points).
    Eigen::MatrixXd A(landmark.observations.size(), 4);
    for (size_t k = 0; k < landmark.observations.size(); ++k) {
      const LineObservation& observation = landmark.observations[k];
      const Eigen::Vector3d l = observation.p0.homogeneous().cross(observation.p1.homogeneous());
      const Eigen::Vector4d plane = odometry_P[observation.frame].transpose() * l;
      A.row(k) = plane.transpose() / plane.head<3>().norm();
    }
    const Eigen::Matrix4d V = Eigen::JacobiSVD<Eigen::MatrixXd>(A, Eigen::ComputeFullV).matrixV();
    const Eigen::Vector4d X2 = V.col(2), X3 = V.col(3);
    const Eigen::Vector4d finite = std::abs(X2.w()) > std::abs(X3.w()) ? X2 : X3;
    Eigen::Vector3d direction = X3.w() * X2.head<3>() - X2.w() * X3.head<3>();
    if (!(std::abs(finite.w()) > 1e-12 && direction.norm() > 1e-12)) continue;
    direction.normalize();
    if (direction.dot(segment.b - segment.a) < 0) direction = -direction;
    landmark.point = finite.hnormalized();
    landmark.direction = direction;
    landmark.end0 = landmark.point + direction * direction.dot(segment.a - landmark.point);
    landmark.end1 = landmark.point + direction * direction.dot(segment.b - landmark.point);
    const auto junction = landmark_of_point.find(segment.point_at_a);
    landmark.point_landmark = junction == landmark_of_point.end() ? -1 : junction->second;
    observed.landmarks.lines.push_back(landmark);
    observed.true_segments.push_back(segment);
  }
  return observed;
}

std::vector<Eigen::Vector3d> CameraPositions(const std::vector<Pose3>& world_T_base,
                                             const Pose3& base_T_camera) {
  std::vector<Eigen::Vector3d> positions;
  for (const Pose3& pose : world_T_base) positions.push_back((pose * base_T_camera).translation);
  return positions;
}

double PositionRmse(const std::vector<Eigen::Vector3d>& estimated,
                    const std::vector<Eigen::Vector3d>& truth) {
  CHECK_EQ(estimated.size(), truth.size());
  CHECK(!truth.empty());
  double sum = 0;
  for (size_t i = 0; i < truth.size(); ++i) sum += (estimated[i] - truth[i]).squaredNorm();
  return std::sqrt(sum / truth.size());
}

double PositionRmseAfterScaling(const std::vector<Eigen::Vector3d>& estimated,
                                const std::vector<Eigen::Vector3d>& truth, double* scale) {
  CHECK_EQ(estimated.size(), truth.size());
  CHECK(!truth.empty());
  // Least squares: min_s sum |t_0 + s (e_i - e_0) - t_i|^2.
  double numerator = 0, denominator = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    numerator += (estimated[i] - estimated[0]).dot(truth[i] - truth[0]);
    denominator += (estimated[i] - estimated[0]).squaredNorm();
  }
  const double s = denominator > 0 ? numerator / denominator : 1.0;
  if (scale != nullptr) *scale = s;
  std::vector<Eigen::Vector3d> scaled;
  for (const Eigen::Vector3d& position : estimated)
    scaled.push_back(truth[0] + s * (position - estimated[0]));
  return PositionRmse(scaled, truth);
}

double RotationRpe(const std::vector<Pose3>& estimated, const std::vector<Pose3>& truth) {
  CHECK_EQ(estimated.size(), truth.size());
  CHECK_GE(truth.size(), 2u);
  double sum = 0;
  for (size_t i = 0; i + 1 < truth.size(); ++i) {
    const Pose3 error =
        (truth[i].Inverse() * truth[i + 1]).Inverse() * (estimated[i].Inverse() * estimated[i + 1]);
    const double angle = RotationAngle(error.rotation, Eigen::Quaterniond::Identity());
    sum += angle * angle;
  }
  return std::sqrt(sum / (truth.size() - 1));
}

Status AdjustFromOdometry(const Calibration& calibration, const std::vector<Pose3>& odometry,
                          const BundleAdjustmentOptions& options, Landmarks* landmarks,
                          std::vector<Pose3>* world_T_base_refined, BundleAdjustmentSummary* summary) {
  Reconstruction reconstruction;
  reconstruction.calibration = calibration;
  reconstruction.world_T_base = odometry;
  reconstruction.landmarks = std::move(*landmarks);
  const Status status = BundleAdjust(odometry, /*odometry_scale_start=*/1, options, &reconstruction, summary);
  *landmarks = std::move(reconstruction.landmarks);
  *world_T_base_refined = std::move(reconstruction.world_T_base);
  return status;
}

}  // namespace sfm::testing
