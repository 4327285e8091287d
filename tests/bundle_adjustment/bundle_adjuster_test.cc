// Bundle adjustment end to end on synthetic problems (tests/bundle_adjustment/synthetic_room.h),
// degenerate problems, and bad options / input.
#include "backend/bundle_adjustment/bundle_adjuster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "backend/bundle_adjustment/floor_prior.h"
#include "backend/bundle_adjustment/observability.h"
#include "backend/triangulation/reconstruction.h"
#include "tests/bundle_adjustment/synthetic_room.h"

namespace sfm {
namespace {

using testing::BoxRoom;
using testing::CameraPositions;
using testing::MakeOdometry;
using testing::Observe;
using testing::Observed;
using testing::PositionRmse;
using testing::RobotCalibration;
using testing::RotationRpe;

// The synthetic problem of the issue: odometry 3% too long whose heading drifts. The drift is
// chosen large enough that it, not the scale error, dominates the odometry's position error:
// monocular bundle adjustment cannot observe the scale, so the refined trajectory keeps the 3%
// (docs/bundle_adjustment.md), about 0.075 m RMS on this lap.
constexpr double kPixelNoisePx = 0.3;
constexpr double kScaleError = 0.03;
constexpr double kHeadingNoiseRad = 0.002;  // per frame, sigma
constexpr double kSmallDriftRad = 0.004;    // per frame, for the degenerate problems

Calibration RoomCalibration(double heading_drift_rad) {
  Calibration calibration = RobotCalibration();
  // The noise model as sequence.yaml would state it for this odometry.
  calibration.odometry_noise.translation_sigma = kScaleError;
  calibration.odometry_noise.rotation_sigma = std::hypot(heading_drift_rad, kHeadingNoiseRad);
  return calibration;
}

std::vector<Pose3> Cameras(const std::vector<Pose3>& world_T_base, const Pose3& base_T_camera) {
  std::vector<Pose3> cameras;
  for (const Pose3& pose : world_T_base) cameras.push_back(pose * base_T_camera);
  return cameras;
}

struct Drift {
  double position_rmse_m;         // camera positions, no alignment
  double scaled_position_rmse_m;  // after the best scaling about the first camera
  double rotation_rpe_rad;        // per frame
};

Drift MeasureDrift(const std::vector<Pose3>& world_T_base, const std::vector<Pose3>& truth,
                   const Pose3& base_T_camera) {
  const std::vector<Eigen::Vector3d> estimated = CameraPositions(world_T_base, base_T_camera);
  const std::vector<Eigen::Vector3d> true_positions = CameraPositions(truth, base_T_camera);
  return {PositionRmse(estimated, true_positions),
          testing::PositionRmseAfterScaling(estimated, true_positions, nullptr),
          RotationRpe(Cameras(world_T_base, base_T_camera), Cameras(truth, base_T_camera))};
}

// RMS distance of the refined points from the true ones (metres).
double PointRmse(const Landmarks& landmarks, const Observed& observed) {
  double sum = 0;
  for (const PointLandmark& point : landmarks.points) {
    sum += (point.position - observed.true_points[point.track_id]).squaredNorm();
  }
  return std::sqrt(sum / landmarks.points.size());
}

void ExpectFinite(const std::vector<Pose3>& poses) {
  for (const Pose3& pose : poses) {
    EXPECT_TRUE(pose.translation.allFinite() && pose.rotation.coeffs().allFinite());
  }
}

constexpr int kOutlierTag = -2;  // PointObservation::junction of the observations made outliers

struct RoomRun {
  Drift odometry, refined;
  BundleAdjustmentSummary summary;
  double point_rmse_before_m = 0, point_rmse_after_m = 0;
  int outliers = 0;            // point observations moved by 20 to 40 px
  int outliers_remaining = 0;  // of them, still in the landmarks after bundle adjustment
};

// One counter-clockwise lap of `frames` frames; every 1/outlier_fraction-th point observation (0:
// none) moved 20 to 40 px in a direction that turns by the golden angle from one to the next.
RoomRun RunRoomLoop(int frames, double heading_drift_rad, double outlier_fraction,
                    const BundleAdjustmentOptions& options = BundleAdjustmentOptions(),
                    std::vector<Pose3>* refined_out = nullptr, std::vector<Pose3>* truth_out = nullptr) {
  const Calibration calibration = RoomCalibration(heading_drift_rad);
  const std::vector<Pose3> truth = testing::LoopTrajectory(frames);
  const std::vector<Pose3> odometry =
      MakeOdometry(truth, kScaleError, heading_drift_rad, kHeadingNoiseRad, 7);
  Observed observed = Observe(BoxRoom(), calibration, truth, odometry, kPixelNoisePx, 11);
  RoomRun run;
  if (outlier_fraction > 0) {
    const int every = static_cast<int>(std::round(1 / outlier_fraction));
    int count = 0;
    for (PointLandmark& point : observed.landmarks.points) {
      for (PointObservation& observation : point.observations) {
        if (++count % every != 0) continue;
        const double angle = 2.39996 * count;
        observation.pixel += (20.0 + count % 21) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
        observation.junction = kOutlierTag;
        ++run.outliers;
      }
    }
  }
  run.point_rmse_before_m = PointRmse(observed.landmarks, observed);
  std::vector<Pose3> refined;
  const Status status = testing::AdjustFromOdometry(calibration, odometry, options, &observed.landmarks,
                                                    &refined, &run.summary);
  EXPECT_TRUE(status.ok()) << status.message();
  if (refined_out != nullptr) *refined_out = refined;
  if (truth_out != nullptr) *truth_out = truth;
  run.odometry = MeasureDrift(odometry, truth, calibration.base_T_camera);
  run.refined = MeasureDrift(refined, truth, calibration.base_T_camera);
  run.point_rmse_after_m = PointRmse(observed.landmarks, observed);
  for (const PointLandmark& point : observed.landmarks.points) {
    for (const PointObservation& observation : point.observations) {
      if (observation.junction == kOutlierTag) ++run.outliers_remaining;
    }
  }
  const BundleAdjustmentSummary& s = run.summary;
  std::printf(
      "[ figures  ] %d frames, %d points, %d lines, %d observations (%d outliers): camera position RMSE "
      "%.3f -> %.3f m (after scaling %.3f -> %.3f m), rotation RPE %.5f -> %.5f rad/frame, point RMSE %.3f "
      "-> "
      "%.3f m; %d solves, %d iterations, cost %.1f -> %.1f, %.3f s; removed %d observations, %d + %d "
      "landmarks, unobservable %d + %d; RMS %.3f px (points), %.3f px (lines)\n",
      s.frames, s.points, s.lines, s.observations, run.outliers, run.odometry.position_rmse_m,
      run.refined.position_rmse_m, run.odometry.scaled_position_rmse_m, run.refined.scaled_position_rmse_m,
      run.odometry.rotation_rpe_rad, run.refined.rotation_rpe_rad, run.point_rmse_before_m,
      run.point_rmse_after_m, s.solves, s.iterations, s.initial_cost, s.final_cost, s.time_s,
      s.observations_removed, s.points_removed, s.lines_removed, s.points_unobservable, s.lines_unobservable,
      s.point_rms_px, s.line_rms_px);
  return run;
}

// The figures on a 60-frame lap with 0.008 rad/frame of heading drift: refined camera
// positions (no alignment: the first pose is fixed on the truth) at most one fifth of the
// odometry's RMSE, rotation RPE at most half. With the scale error taken out, at most 1/20.
TEST(BundleAdjusterTest, RoomLoopFromDriftingOdometry) {
  const RoomRun run = RunRoomLoop(60, 0.008, 0);
  EXPECT_LE(run.refined.position_rmse_m, run.odometry.position_rmse_m / 5);
  EXPECT_LE(run.refined.scaled_position_rmse_m, run.odometry.scaled_position_rmse_m / 20);
  EXPECT_LE(run.refined.rotation_rpe_rad, run.odometry.rotation_rpe_rad / 2);
  EXPECT_GE(run.summary.points, 35);
  EXPECT_GE(run.summary.lines, 35);
  EXPECT_TRUE(run.summary.converged);
  EXPECT_EQ(run.summary.observations_removed, 0);  // 0.3 px noise, 3 px threshold
  // The residuals are the pixel noise: sqrt(2) * 0.3 px for a point's 2D error, 0.3 px per end-point.
  EXPECT_LT(run.summary.point_rms_px, 0.5);
  EXPECT_LT(run.summary.line_rms_px, 0.4);
  EXPECT_LT(run.point_rmse_after_m, run.point_rmse_before_m / 2);
}

// The iterative Schur solver (kAuto's choice where revisits fill the reduced system) reaches the
// factorisation's minimum: on the 60-frame lap the refined camera positions agree within 1 mm RMS
// (observed 0.46 mm) and both meet RoomLoopFromDriftingOdometry's bound.
TEST(BundleAdjusterTest, IterativeSchurReachesTheFactorisationsMinimum) {
  BundleAdjustmentOptions options;
  options.linear_solver = BundleAdjustmentLinearSolver::kDenseSchur;
  std::vector<Pose3> dense, iterative, truth;
  const RoomRun run_dense = RunRoomLoop(60, 0.008, 0, options, &dense, &truth);
  options.linear_solver = BundleAdjustmentLinearSolver::kIterativeSchur;
  const RoomRun run_iterative = RunRoomLoop(60, 0.008, 0, options, &iterative);
  const Pose3 base_T_camera = RoomCalibration(0.008).base_T_camera;
  const double apart_m =
      PositionRmse(CameraPositions(iterative, base_T_camera), CameraPositions(dense, base_T_camera));
  std::printf("[ figures  ] iterative against dense Schur: %.6f m RMS apart\n", apart_m);
  EXPECT_LE(apart_m, 0.001);
  EXPECT_LE(run_iterative.refined.position_rmse_m, run_iterative.odometry.position_rmse_m / 5);
  EXPECT_LE(run_dense.refined.position_rmse_m, run_dense.odometry.position_rmse_m / 5);
}

// The solves start from a given trajectory (BundleAdjustment's start poses, e.g. a vision-first
// one), the drifting odometry staying the prior: a 40-frame lap with 0.008 rad/frame of heading
// drift started from the true poses reaches the start from the odometry's camera position RMSE
// within 5 % (observed 0.0743 against 0.0747 m, in 22 iterations against 18: the start is used),
// at most a quarter of the odometry's (0.337 m; the unobservable 3 % scale error is most of what
// is left), and the rotation RPE at most half the odometry's. A start the
// adjustment cannot use is an error naming it: not as many poses as the odometry, a first pose
// other than the odometry's (the gauge), a scale factor not > 0.
TEST(BundleAdjusterTest, StartsFromAGivenTrajectory) {
  const Calibration calibration = RoomCalibration(0.008);
  const std::vector<Pose3> truth = testing::LoopTrajectory(40);
  const std::vector<Pose3> odometry = MakeOdometry(truth, kScaleError, 0.008, kHeadingNoiseRad, 7);
  const Observed observed = Observe(BoxRoom(), calibration, truth, odometry, kPixelNoisePx, 11);
  auto adjust = [&](std::vector<Pose3> start, double scale, BundleAdjustmentSummary* summary) {
    Reconstruction reconstruction;
    reconstruction.calibration = calibration;
    reconstruction.world_T_base = std::move(start);
    reconstruction.landmarks = observed.landmarks;
    const Status status = BundleAdjust(odometry, scale, BundleAdjustmentOptions(), &reconstruction, summary);
    return std::make_pair(status, reconstruction.world_T_base);
  };
  std::vector<Pose3> start = truth;
  start[0] = odometry[0];
  BundleAdjustmentSummary from_truth_summary, from_odometry_summary;
  const auto [status, from_truth] = adjust(start, 1, &from_truth_summary);
  ASSERT_TRUE(status.ok()) << status.message();
  const auto [odometry_status, from_odometry] = adjust(odometry, 1, &from_odometry_summary);
  ASSERT_TRUE(odometry_status.ok()) << odometry_status.message();
  const Drift before = MeasureDrift(odometry, truth, calibration.base_T_camera);
  const Drift after = MeasureDrift(from_truth, truth, calibration.base_T_camera);
  const Drift after_odometry = MeasureDrift(from_odometry, truth, calibration.base_T_camera);
  std::printf(
      "[ figures  ] camera position RMSE: odometry %.4f m, refined from the true poses %.4f m (%d "
      "iterations), from the odometry %.4f m (%d iterations); rotation RPE %.5f -> %.5f rad\n",
      before.position_rmse_m, after.position_rmse_m, from_truth_summary.iterations,
      after_odometry.position_rmse_m, from_odometry_summary.iterations, before.rotation_rpe_rad,
      after.rotation_rpe_rad);
  EXPECT_LE(after.position_rmse_m, 1.05 * after_odometry.position_rmse_m);
  EXPECT_LE(after.position_rmse_m, before.position_rmse_m / 4);
  EXPECT_LE(after.rotation_rpe_rad, before.rotation_rpe_rad / 2);

  BundleAdjustmentSummary summary;
  std::vector<Pose3> short_start(start.begin(), start.end() - 1);
  EXPECT_NE(adjust(short_start, 1, &summary).first.message().find("start poses"), std::string::npos);
  std::vector<Pose3> moved = start;
  moved[0].translation.x() += 0.1;
  EXPECT_NE(adjust(moved, 1, &summary).first.message().find("gauge"), std::string::npos);
  EXPECT_NE(adjust(start, 0, &summary).first.message().find("scale"), std::string::npos);
}

// One point observation in 20 is a gross mismatch: all of them are removed, few others, and the
// figures hold (40 frames, 0.012 rad/frame of drift).
TEST(BundleAdjusterTest, OutliersAreRemoved) {
  const RoomRun run = RunRoomLoop(40, 0.012, 0.05);
  ASSERT_GT(run.outliers, 10);
  EXPECT_EQ(run.outliers_remaining, 0);
  // 1.4x with the along/across odometry prior (21 for 15: 13 at the coarse 20 px, 8 at 3 px; the
  // isotropic prior removed 14, 8 + 6): the coarse solve from 0.012 rad/frame of drift leaves more
  // inliers beyond 20 px. Bound: half as many again as injected.
  EXPECT_LE(run.summary.observations_removed, run.outliers + run.outliers / 2);
  EXPECT_LE(run.refined.position_rmse_m, run.odometry.position_rmse_m / 5);
  EXPECT_LE(run.refined.rotation_rpe_rad, run.odometry.rotation_rpe_rad / 2);
  EXPECT_LT(run.summary.point_rms_px, 0.5);
}

TEST(BundleAdjusterTest, NoMotionDropsEveryLandmark) {
  Calibration calibration = RoomCalibration(kSmallDriftRad);
  const std::vector<Pose3> truth(10, testing::LoopTrajectory(1).front());
  Observed observed = Observe(BoxRoom(), calibration, truth, truth, kPixelNoisePx, 3);
  // Triangulation from one viewpoint is meaningless: give the landmarks their true positions.
  for (size_t i = 0; i < observed.landmarks.points.size(); ++i) {
    observed.landmarks.points[i].position = observed.true_points[i];
  }
  for (size_t i = 0; i < observed.landmarks.lines.size(); ++i) {
    observed.landmarks.lines[i].point = observed.true_segments[i].a;
    observed.landmarks.lines[i].direction = observed.true_segments[i].b - observed.true_segments[i].a;
  }
  const int points = static_cast<int>(observed.landmarks.points.size());
  const int lines = static_cast<int>(observed.landmarks.lines.size());
  ASSERT_GT(points, 0);
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  const Status status = testing::AdjustFromOdometry(calibration, truth, BundleAdjustmentOptions(),
                                                    &observed.landmarks, &refined, &summary);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(summary.points_unobservable, points);
  EXPECT_EQ(summary.lines_unobservable, lines);
  EXPECT_EQ(summary.solves, 0);
  EXPECT_TRUE(observed.landmarks.points.empty() && observed.landmarks.lines.empty());
  ASSERT_EQ(refined.size(), truth.size());
  for (size_t f = 0; f < truth.size(); ++f)
    EXPECT_NEAR((refined[f].translation - truth[f].translation).norm(), 0, 1e-12);
}

// The robot stands still but the odometry moves the camera by a millimetre or two (as the
// generator's heading noise does through the 0.2 m lever arm), and the landmarks were intersected
// 2-4 cm from the camera centres (where a degenerate triangulation puts them). From there the
// millimetre baseline is seen at several degrees, so the angle checks alone keep them; the depth
// floor on the refined landmarks drops every one, and the trajectory is the odometry's.
TEST(BundleAdjusterTest, LandmarksNextToTheCamerasAreDropped) {
  Calibration calibration = RoomCalibration(kSmallDriftRad);
  const Pose3 still = testing::LoopTrajectory(1).front();
  std::vector<Pose3> jittered;
  for (int i = 0; i < 8; ++i) {
    const double yaw = 0.006 * ((i * 5) % 7 - 3) / 3.0;  // up to 6 mrad: 1.2 mm at the camera
    jittered.push_back(still * Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())),
                                     Eigen::Vector3d::Zero()));
  }
  const std::vector<Pose3> truth(jittered.size(), still);
  Observed observed = Observe(BoxRoom(), calibration, truth, truth, kPixelNoisePx, 3);
  const Pose3 camera = still * calibration.base_T_camera;
  auto near = [&](const Eigen::Vector3d& x, double depth) -> Eigen::Vector3d {
    return camera.translation + depth * (x - camera.translation).normalized();
  };
  for (size_t i = 0; i < observed.landmarks.points.size(); ++i) {
    observed.landmarks.points[i].position = near(observed.true_points[i], 0.02 + 0.002 * (i % 10));
  }
  for (size_t i = 0; i < observed.landmarks.lines.size(); ++i) {
    LineLandmark& line = observed.landmarks.lines[i];
    line.end0 = near(observed.true_segments[i].a, 0.03);
    line.end1 = near(observed.true_segments[i].b, 0.03);
    line.point = line.end0;
    line.direction = (line.end1 - line.end0).normalized();
  }
  const int points = static_cast<int>(observed.landmarks.points.size());
  const int lines = static_cast<int>(observed.landmarks.lines.size());
  ASSERT_GT(points, 0);
  ASSERT_GT(lines, 0);
  // The angles alone: some points pass.
  int points_with_angle = 0;
  for (const PointLandmark& point : observed.landmarks.points) {
    std::vector<Eigen::Vector3d> centres;
    for (const PointObservation& observation : point.observations)
      centres.push_back((jittered[observation.frame] * calibration.base_T_camera).translation);
    if (PointTriangulationAngleDeg(point.position, centres) >= 1.0) ++points_with_angle;
  }
  EXPECT_GT(points_with_angle, 0);
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  const Status status = testing::AdjustFromOdometry(calibration, jittered, BundleAdjustmentOptions(),
                                                    &observed.landmarks, &refined, &summary);
  ASSERT_TRUE(status.ok()) << status.message();
  std::printf("[ figures  ] next to the cameras: %d points, %d lines; unobservable %d + %d, removed %d + %d\n",
              points, lines, summary.points_unobservable, summary.lines_unobservable, summary.points_removed,
              summary.lines_removed);
  EXPECT_TRUE(observed.landmarks.points.empty());
  EXPECT_TRUE(observed.landmarks.lines.empty());
  EXPECT_GT(summary.points_unobservable, points / 2);
  ASSERT_EQ(refined.size(), jittered.size());
  for (size_t f = 0; f < jittered.size(); ++f)
    EXPECT_NEAR((refined[f].translation - jittered[f].translation).norm(), 0, 1e-12);
}

TEST(ObservabilityTest, SmallestDepth) {
  const Pose3 identity;
  const Pose3 turned(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY())),
                     Eigen::Vector3d(0, 0, 0));  // camera z along world x
  EXPECT_DOUBLE_EQ(SmallestDepth({Eigen::Vector3d(0.5, 0, 2), Eigen::Vector3d(0, 0, 3)}, {identity}), 2);
  EXPECT_DOUBLE_EQ(SmallestDepth({Eigen::Vector3d(0.5, 0, 2)}, {identity, turned}), 0.5);
  EXPECT_TRUE(std::isinf(SmallestDepth({}, {identity})));
}

// The base turns in place: the camera, 0.2 m ahead of the turning axis, still sees some parallax.
// With the camera on the axis (forward = 0) nothing is observable.
TEST(BundleAdjusterTest, PureRotation) {
  for (const double forward : {0.2, 0.0}) {
    Calibration calibration = RobotCalibration(forward, 1.0);
    calibration.odometry_noise = RoomCalibration(kSmallDriftRad).odometry_noise;
    std::vector<Pose3> truth;
    for (int i = 0; i < 12; ++i) {
      truth.emplace_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.08 * i, Eigen::Vector3d::UnitZ())),
                         Eigen::Vector3d(4, 3, 0));
    }
    const std::vector<Pose3> odometry = MakeOdometry(truth, kScaleError, kSmallDriftRad, kHeadingNoiseRad, 5);
    Observed observed = Observe(BoxRoom(), calibration, truth, odometry, kPixelNoisePx, 5);
    std::vector<Pose3> refined;
    BundleAdjustmentSummary summary;
    const Status status = testing::AdjustFromOdometry(calibration, odometry, BundleAdjustmentOptions(),
                                                      &observed.landmarks, &refined, &summary);
    ASSERT_TRUE(status.ok()) << status.message();
    ASSERT_EQ(refined.size(), truth.size());
    ExpectFinite(refined);
    if (forward == 0) {
      EXPECT_EQ(summary.solves, 0);
      EXPECT_EQ(summary.points, 0);
      EXPECT_EQ(summary.lines, 0);
    } else {
      // Whatever stays observable must not make the rotations worse than the odometry's.
      EXPECT_LE(RotationRpe(refined, truth), RotationRpe(odometry, truth));
    }
  }
}

TEST(BundleAdjusterTest, SingleLandmark) {
  const Calibration calibration = RoomCalibration(kSmallDriftRad);
  const std::vector<Pose3> truth = testing::StraightTrajectory(10, {1.5, 3.0}, 0.2);
  const std::vector<Pose3> odometry = MakeOdometry(truth, kScaleError, kSmallDriftRad, kHeadingNoiseRad, 9);
  testing::Scene scene;
  scene.points.emplace_back(7.0, 3.5, 1.5);
  Observed observed = Observe(scene, calibration, truth, odometry, kPixelNoisePx, 9);
  ASSERT_EQ(observed.landmarks.points.size(), 1u);
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  const Status status = testing::AdjustFromOdometry(calibration, odometry, BundleAdjustmentOptions(),
                                                    &observed.landmarks, &refined, &summary);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(summary.points, 1);
  EXPECT_GE(summary.solves, 1);
  ExpectFinite(refined);
  // One point cannot correct much, and must not make the trajectory worse than the odometry.
  EXPECT_LE(PositionRmse(CameraPositions(refined, calibration.base_T_camera),
                         CameraPositions(truth, calibration.base_T_camera)),
            1.1 * PositionRmse(CameraPositions(odometry, calibration.base_T_camera),
                               CameraPositions(truth, calibration.base_T_camera)));
}

// Yaw of world_T_base (rad), for the heading drift of a trajectory driven on the floor.
double Yaw(const Pose3& pose) {
  const Eigen::Vector3d x = pose.rotation * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

struct BiasRun {
  BundleAdjustmentSummary summary;
  double realized_bias_rad = 0;  // mean per-step yaw error of the odometry (the bias plus the noise's mean)
  double odometry_final_yaw_rad = 0;  // |yaw error| of the last frame
  double refined_final_yaw_rad = 0;
  double refined_rms_yaw_rad = 0;  // RMS yaw error over the frames
};

// A 60-frame straight drive down the room (as the generated corridors: 0.09 m steps) with odometry
// whose every step turns 0.001 rad too far left (the generator's heading_bias) plus 0.002 rad of
// noise; the noise model's rotation sigma is sqrt(0.001^2 + 0.002^2), as the generator states it.
BiasRun RunBiasedDrive(bool estimate_bias) {
  constexpr int kFrames = 60;
  constexpr double kBias = 0.001;
  Calibration calibration = RoomCalibration(kBias);
  const std::vector<Pose3> truth = testing::StraightTrajectory(kFrames, {1.0, 3.0}, 0.09);
  const std::vector<Pose3> odometry = MakeOdometry(truth, 0.02, kBias, kHeadingNoiseRad, 5);
  Observed observed = Observe(BoxRoom(), calibration, truth, odometry, kPixelNoisePx, 5);
  BundleAdjustmentOptions options;
  options.estimate_odometry_rotation_bias = estimate_bias;
  options.estimate_odometry_rotation_bias_on_floor = false;  // not auto: this rig passes the floor's check
  BiasRun run;
  std::vector<Pose3> refined;
  const Status status = testing::AdjustFromOdometry(calibration, odometry, options, &observed.landmarks,
                                                    &refined, &run.summary);
  EXPECT_TRUE(status.ok()) << status.message();
  run.realized_bias_rad = (Yaw(odometry.back()) - Yaw(odometry.front())) / (kFrames - 1);
  run.odometry_final_yaw_rad = std::abs(Yaw(odometry.back()) - Yaw(truth.back()));
  run.refined_final_yaw_rad = std::abs(Yaw(refined.back()) - Yaw(truth.back()));
  double sum = 0;
  for (size_t f = 0; f < refined.size(); ++f) sum += std::pow(Yaw(refined[f]) - Yaw(truth[f]), 2);
  run.refined_rms_yaw_rad = std::sqrt(sum / refined.size());
  const std::array<double, 3>& b = run.summary.odometry_rotation_bias_rad;
  std::printf(
      "[ figures  ] bias %s: b = (%.6f, %.6f, %.6f) rad, realized %.6f rad/step; final yaw error %.5f -> "
      "%.5f rad, RMS %.5f rad\n",
      estimate_bias ? "estimated" : "not estimated", b[0], b[1], b[2], run.realized_bias_rad,
      run.odometry_final_yaw_rad, run.refined_final_yaw_rad, run.refined_rms_yaw_rad);
  return run;
}

// Issue 5: the odometry's constant heading bias estimated with the poses. b's yaw comes out at the
// odometry's realized per-step bias (0.001 rad plus the mean of 59 draws of 0.002 rad noise) to
// 1e-4 rad (a tenth of the bias; the zero-mean prior shrinks it by 1/60 of itself, 2e-5), its
// other components below 1e-4 rad (observed: b = (2e-6, -4e-6, 0.001110), realized 0.001135).
// The room's many landmarks already hold the yaw well without b (1.28 mrad at the last frame,
// where the corridors keep 6.5 mrad); with b the last frame's yaw error falls to less than a third
// of that (observed 0.33 mrad); the RMS over the drive, which the room's landmarks hold to 0.3 mrad
// either way (frame-to-frame noise, not drift), grows by at most 10 % (observed 0.300 -> 0.308 mrad).
TEST(BundleAdjusterTest, OdometryRotationBiasIsEstimated) {
  const BiasRun without = RunBiasedDrive(false);
  const BiasRun with = RunBiasedDrive(true);
  const std::array<double, 3>& b = with.summary.odometry_rotation_bias_rad;
  EXPECT_NEAR(b[2], with.realized_bias_rad, 1e-4);
  EXPECT_LT(std::hypot(b[0], b[1]), 1e-4);
  EXPECT_TRUE(with.summary.odometry_rotation_bias_estimated);
  const std::array<double, 3>& none = without.summary.odometry_rotation_bias_rad;
  EXPECT_EQ(none[0] == 0 && none[1] == 0 && none[2] == 0, true);
  EXPECT_LT(with.refined_final_yaw_rad, without.refined_final_yaw_rad / 3);
  EXPECT_LE(with.refined_rms_yaw_rad, 1.1 * without.refined_rms_yaw_rad);
}

// Driving straight along x: every edge along x lies in one plane with all the camera centres, so
// its depth in that plane is free; so does an edge in the vertical plane of the path. Exactly the
// lines whose true geometry gives a triangulation angle below the minimum are dropped and counted,
// among them every edge along x.
TEST(BundleAdjusterTest, LinesParallelToTheMotionAreDropped) {
  const Calibration calibration = RoomCalibration(kSmallDriftRad);
  const std::vector<Pose3> truth = testing::StraightTrajectory(20, {1.0, 2.5}, 0.15);
  // Odometry with its scale error but no heading noise: the drift would bend the path.
  const std::vector<Pose3> odometry = MakeOdometry(truth, kScaleError, 0, 0, 1);
  Observed observed = Observe(BoxRoom(), calibration, truth, odometry, kPixelNoisePx, 13);
  const BundleAdjustmentOptions options;
  int parallel = 0, unobservable = 0;
  for (size_t i = 0; i < observed.true_segments.size(); ++i) {
    const testing::Scene::Segment& segment = observed.true_segments[i];
    std::vector<Eigen::Vector3d> centres;
    for (const LineObservation& observation : observed.landmarks.lines[i].observations) {
      centres.push_back((truth[observation.frame] * calibration.base_T_camera).translation);
    }
    if (LineTriangulationAngleDeg(segment.a, segment.b - segment.a, centres) <
        options.min_line_triangulation_angle_deg) {
      ++unobservable;
    }
    if ((segment.b - segment.a).normalized().cross(Eigen::Vector3d::UnitX()).norm() < 1e-9) ++parallel;
  }
  ASSERT_GT(parallel, 0);
  ASSERT_GT(static_cast<int>(observed.true_segments.size()), unobservable);
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  const Status status =
      testing::AdjustFromOdometry(calibration, odometry, options, &observed.landmarks, &refined, &summary);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_GE(unobservable, parallel);
  EXPECT_EQ(summary.lines_unobservable, unobservable);
  EXPECT_GT(summary.lines, 0);
  for (const LineLandmark& line : observed.landmarks.lines) {
    EXPECT_GT(line.direction.normalized().cross(Eigen::Vector3d::UnitX()).norm(), 0.1);
  }
  ExpectFinite(refined);
}

// The landmarks that fail the adjustment's observability rules on the poses world_T_base: a point
// less than min_depth_m deep in a camera that sees it or seen at less than the minimum angle; a line
// whose part a view observes is less than min_depth_m deep (or behind the camera), or with less
// triangulation angle (or back-projected planes' angle) than the minimum.
int UnobservableLandmarks(const Calibration& calibration, const std::vector<Pose3>& world_T_base,
                          const Landmarks& landmarks, const BundleAdjustmentOptions& options) {
  const Eigen::Matrix3d K = calibration.camera.K();
  int count = 0;
  for (const PointLandmark& point : landmarks.points) {
    std::vector<Pose3> cameras;
    std::vector<Eigen::Vector3d> centres;
    for (const PointObservation& observation : point.observations) {
      cameras.push_back(world_T_base[observation.frame] * calibration.base_T_camera);
      centres.push_back(cameras.back().translation);
    }
    if (!(SmallestDepth({point.position}, cameras) >= options.min_depth_m) ||
        !(PointTriangulationAngleDeg(point.position, centres) >= options.min_point_triangulation_angle_deg)) {
      ++count;
    }
  }
  for (const LineLandmark& line : landmarks.lines) {
    double depth = std::numeric_limits<double>::infinity();
    std::vector<Eigen::Vector3d> centres, normals;
    for (const LineObservation& observation : line.observations) {
      const Pose3 camera = world_T_base[observation.frame] * calibration.base_T_camera;
      depth = std::min(depth, ObservedLineDepth(K, camera, observation.p0, observation.p1, line.point,
                                                line.direction));
      centres.push_back(camera.translation);
      normals.push_back(BackProjectedPlaneNormal(K, camera.RotationMatrix(), observation.p0, observation.p1));
    }
    const double angle_deg =
        std::min(LineTriangulationAngleDeg(line.point, line.direction, centres), LargestPlaneAngleDeg(normals));
    if (!(depth >= options.min_depth_m) || !(angle_deg >= options.min_line_triangulation_angle_deg)) ++count;
  }
  return count;
}

// A landmark that the last solve makes unobservable is not left in the output (docs/bundle_adjustment.md,
// "Robust loss, stages and outliers", step 7). Frame 20 of a lap sees no point, and its odometry has
// camera 20 pitched by 0.02 rad (exact elsewhere; the noise model allows it), so it stays there
// through the points-only coarse solve and only the joint solve, where its lines pull it back,
// corrects it. One more line is seen from frames 19 and 20, 9.5 cm in front of camera 20 across its
// view: on the odometry's poses its two back-projected planes meet 13 cm in front, above the 10 cm
// depth floor, so it passes every check before the last solve; on the corrected poses it is 9.5 cm
// deep and fails the same check after it. With outlier_rounds = 0 the joint solve is the last: the
// line is dropped after it (counted in landmarks_unobservable_after_last_solve, one solve more)
// and no unobservable landmark is left. (A two-view line fits exactly and holds no pose: nothing else moves here; on
// Strecha such lines had three views and bent the trajectory.)
TEST(BundleAdjusterTest, TheLastSolveLeavesNoUnobservableLandmark) {
  Calibration calibration = RoomCalibration(kSmallDriftRad);
  calibration.odometry_noise.rotation_sigma = 0.05;  // the noise model allows frame 20's error
  const Eigen::Matrix3d K = calibration.camera.K();
  const std::vector<Pose3> truth = testing::LoopTrajectory(40);
  constexpr int kFrame = 20;
  std::vector<Pose3> odometry = truth;
  // Camera 20 pitched about its centre.
  constexpr double kPitchRad = 0.02;  // 9 px at the image's edge: within the coarse 20 px
  odometry[kFrame] = truth[kFrame] * calibration.base_T_camera *
                     Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(kPitchRad, Eigen::Vector3d::UnitX())),
                           Eigen::Vector3d::Zero()) *
                     calibration.base_T_camera.Inverse();
  Observed observed = Observe(BoxRoom(), calibration, truth, odometry, kPixelNoisePx, 11);
  for (PointLandmark& point : observed.landmarks.points) {
    auto& observations = point.observations;
    observations.erase(std::remove_if(observations.begin(), observations.end(),
                                      [](const PointObservation& observation) { return observation.frame == kFrame; }),
                       observations.end());
  }
  // The line 9.5 cm in front of camera 20, across its view, seen exactly from the true poses.
  const Pose3 camera_b = truth[kFrame] * calibration.base_T_camera;
  const Eigen::Vector3d end_a = camera_b * Eigen::Vector3d(-0.05, 0.01, 0.095);
  const Eigen::Vector3d end_b = camera_b * Eigen::Vector3d(0.05, 0.01, 0.095);
  LineLandmark line;
  for (int frame : {kFrame - 1, kFrame}) {
    const Pose3 camera = truth[frame] * calibration.base_T_camera;
    LineObservation observation;
    observation.frame = frame;
    observation.p0 = (K * (camera.Inverse() * end_a)).hnormalized();
    observation.p1 = (K * (camera.Inverse() * end_b)).hnormalized();
    line.observations.push_back(observation);
  }
  // Its estimate on the odometry's poses: the intersection of its two back-projected planes.
  std::vector<Eigen::Vector3d> normals, centres;
  for (const LineObservation& observation : line.observations) {
    const Pose3 camera = odometry[observation.frame] * calibration.base_T_camera;
    normals.push_back(BackProjectedPlaneNormal(K, camera.RotationMatrix(), observation.p0, observation.p1));
    centres.push_back(camera.translation);
  }
  line.direction = normals[0].cross(normals[1]).normalized();
  Eigen::Matrix3d planes;
  planes << normals[0].transpose(), normals[1].transpose(), line.direction.transpose();
  line.point = planes.inverse() * Eigen::Vector3d(normals[0].dot(centres[0]), normals[1].dot(centres[1]),
                                                   line.direction.dot(end_a));
  line.end0 = line.point;
  line.end1 = line.point + line.direction;
  const Pose3 camera_b_odometry = odometry[kFrame] * calibration.base_T_camera;
  const double odometry_depth_m = ObservedLineDepth(K, camera_b_odometry, line.observations[1].p0,
                                                    line.observations[1].p1, line.point, line.direction);
  observed.landmarks.lines.push_back(line);
  const BundleAdjustmentOptions defaults;
  ASSERT_GT(odometry_depth_m, defaults.min_depth_m);

  BundleAdjustmentOptions options;
  options.outlier_rounds = 0;
  Landmarks landmarks = observed.landmarks;
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  const Status status =
      testing::AdjustFromOdometry(calibration, odometry, options, &landmarks, &refined, &summary);
  ASSERT_TRUE(status.ok()) << status.message();
  const int unobservable = UnobservableLandmarks(calibration, refined, landmarks, options);
  const double rotation_error_rad =
      Eigen::AngleAxisd(truth[kFrame].rotation.inverse() * refined[kFrame].rotation).angle();
  std::printf("[ figures  ] the near line %.3f m deep on the odometry; %d dropped after the last solve, %d "
              "unobservable landmarks left, %d solves, frame %d rotation error %.3f -> %.4f rad\n",
              odometry_depth_m, summary.landmarks_unobservable_after_last_solve, unobservable, summary.solves,
              kFrame, kPitchRad, rotation_error_rad);
  // The joint solve corrected the frame (what makes the line fail): at most a fifth left (0.0021
  // observed, the level of the lap's other frames).
  EXPECT_LT(rotation_error_rad, kPitchRad / 5);
  EXPECT_GE(summary.landmarks_unobservable_after_last_solve, 1);
  EXPECT_GE(summary.observability_solves, 1);
  EXPECT_EQ(unobservable, 0);
}

TEST(BundleAdjusterTest, NothingToSolve) {
  const Calibration calibration = RoomCalibration(kSmallDriftRad);
  Landmarks landmarks;
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  const std::vector<Pose3> one_frame = {testing::LoopTrajectory(1).front()};
  ASSERT_TRUE(testing::AdjustFromOdometry(calibration, one_frame, BundleAdjustmentOptions(), &landmarks,
                                          &refined, &summary)
                  .ok());
  EXPECT_EQ(refined.size(), 1u);
  EXPECT_EQ(summary.solves, 0);
  const std::vector<Pose3> odometry = testing::LoopTrajectory(5);
  ASSERT_TRUE(testing::AdjustFromOdometry(calibration, odometry, BundleAdjustmentOptions(), &landmarks,
                                          &refined, &summary)
                  .ok());
  ASSERT_EQ(refined.size(), odometry.size());
  for (size_t f = 0; f < odometry.size(); ++f)
    EXPECT_NEAR((refined[f].translation - odometry[f].translation).norm(), 0, 1e-12);
}

TEST(BundleAdjusterTest, BadInputIsAnError) {
  const Calibration good = RoomCalibration(kSmallDriftRad);
  const std::vector<Pose3> odometry = testing::LoopTrajectory(5);
  std::vector<Pose3> refined;
  BundleAdjustmentSummary summary;
  Landmarks landmarks;
  EXPECT_FALSE(
      testing::AdjustFromOdometry(good, {}, BundleAdjustmentOptions(), &landmarks, &refined, &summary).ok());
  Calibration no_noise = good;
  no_noise.odometry_noise.rotation_sigma = 0;
  EXPECT_FALSE(testing::AdjustFromOdometry(no_noise, odometry, BundleAdjustmentOptions(), &landmarks,
                                           &refined, &summary)
                   .ok());
  landmarks.points.resize(1);
  landmarks.points[0].observations = {{0, 0, {1, 1}}, {5, 0, {1, 1}}};  // frame 5 of 5
  const Status status =
      testing::AdjustFromOdometry(good, odometry, BundleAdjustmentOptions(), &landmarks, &refined, &summary);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("frame 5"), std::string::npos) << status.message();
}

TEST(BundleAdjustmentOptionsTest, CheckNamesTheBadField) {
  EXPECT_TRUE(BundleAdjustmentOptions().Check().ok());
  auto message = [](void (*change)(BundleAdjustmentOptions*)) {
    BundleAdjustmentOptions options;
    change(&options);
    return options.Check().message();
  };
  EXPECT_NE(
      message([](BundleAdjustmentOptions* o) { o->robust_loss_scale_px = 0; }).find("robust_loss_scale_px"),
      std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) { o->max_iterations = 0; }).find("max_iterations"),
            std::string::npos);
  EXPECT_NE(
      message([](BundleAdjustmentOptions* o) { o->outlier_threshold_px = -1; }).find("outlier_threshold_px"),
      std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) { o->outlier_rounds = -1; }).find("outlier_rounds"),
            std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) {
              o->odometry_min_distance_m = 0;
            }).find("odometry_min_distance_m"),
            std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) { o->min_depth_m = -1; }).find("min_depth_m"),
            std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) { o->function_tolerance = 0; }).find("function_tolerance"),
            std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) {
              o->intermediate_function_tolerance = 1;
            }).find("intermediate_function_tolerance"),
            std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) {
              o->min_line_triangulation_angle_deg = 90;
            }).find("min_line_triangulation_angle_deg"),
            std::string::npos);
  EXPECT_NE(message([](BundleAdjustmentOptions* o) {
              o->iterative_schur_min_cells_per_frame = 0;
            }).find("iterative_schur_min_cells_per_frame"),
            std::string::npos);
}

// ---- Floor prior (docs/bundle_adjustment.md, "Floor prior") ----

struct FloorRun {
  Drift odometry, refined;
  double odometry_scale = 0;  // best scale of the odometry's camera positions onto the truth's
  double refined_scale = 0;   // the same for the refined ones
  std::vector<Pose3> world_T_base_refined;
  BundleAdjustmentSummary summary;
};

// A 60-frame lap of the room with rugs with 3 % too long odometry and a little heading drift
// (0.004 rad/frame: the scale error dominates), the scene moved to floor_z and the camera
// `camera_height` m above the base origin.
FloorRun RunFloorLoop(double floor_z, double camera_height, FloorPriorMode mode,
                      const std::vector<Eigen::Vector3d>& extra_points = {}, bool bias_on_floor = true,
                      double scale_error = kScaleError, double function_tolerance = 0,
                      int floor_start_min_frames = BundleAdjustmentOptions().floor_start_min_frames) {
  Calibration calibration = RoomCalibration(kSmallDriftRad);
  calibration.base_T_camera.translation.z() = camera_height;
  const std::vector<Pose3> truth = testing::LoopTrajectory(60);
  const std::vector<Pose3> odometry = MakeOdometry(truth, scale_error, kSmallDriftRad, kHeadingNoiseRad, 7);
  testing::Scene scene = testing::BoxRoomWithRugs(floor_z);
  scene.points.insert(scene.points.end(), extra_points.begin(), extra_points.end());
  Observed observed = Observe(scene, calibration, truth, odometry, kPixelNoisePx, 11);
  BundleAdjustmentOptions options;
  options.floor_prior = mode;
  options.estimate_odometry_rotation_bias_on_floor = bias_on_floor;
  options.floor_start_min_frames = floor_start_min_frames;
  if (function_tolerance > 0) {
    options.function_tolerance = function_tolerance;
    options.intermediate_function_tolerance = std::max(function_tolerance, options.intermediate_function_tolerance);
  }
  FloorRun run;
  const Status status = testing::AdjustFromOdometry(calibration, odometry, options, &observed.landmarks,
                                                    &run.world_T_base_refined, &run.summary);
  EXPECT_TRUE(status.ok()) << status.message();
  run.odometry = MeasureDrift(odometry, truth, calibration.base_T_camera);
  run.refined = MeasureDrift(run.world_T_base_refined, truth, calibration.base_T_camera);
  const auto true_positions = CameraPositions(truth, calibration.base_T_camera);
  testing::PositionRmseAfterScaling(CameraPositions(odometry, calibration.base_T_camera), true_positions,
                                    &run.odometry_scale);
  testing::PositionRmseAfterScaling(CameraPositions(run.world_T_base_refined, calibration.base_T_camera),
                                    true_positions, &run.refined_scale);
  std::printf("[ figures  ] floor at %.2f m, camera %.2f m above the base: camera position RMSE %.4f -> %.4f m, "
              "scale onto the truth %.4f -> %.4f; %s (odometry scale %.4f)\n",
              floor_z, camera_height, run.odometry.position_rmse_m, run.refined.position_rmse_m, run.odometry_scale,
              run.refined_scale, run.summary.floor_prior_report.c_str(), run.summary.odometry_scale);
  return run;
}

// 3 % too long odometry: with the floor prior (auto) the refined trajectory's scale is right to
// 0.5 % (a sixth of the error; observed 0.9993, 0.9970 without the base poses held on the floor,
// against 0.9771 without the prior: the scale that maps the refined camera positions onto the true
// ones about the first), the odometry's scale factor found is 1/1.03 to 0.012 (observed 0.9730;
// 0.9759 without the base prior), and the camera positions are within a fifth of the odometry's
// RMSE (observed 0.2397 -> 0.0026 m with the rotation bias that auto now estimates, 0.0037 m
// without it, 0.0109 m without the base prior), which the same run without the floor prior does
// not reach (0.0687 m).
TEST(FloorPriorTest, ThreePercentScaleErrorIsCorrected) {
  const FloorRun with = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto);
  const FloorRun without = RunFloorLoop(0, 1.0, FloorPriorMode::kOff);
  EXPECT_TRUE(with.summary.floor_prior_used) << with.summary.floor_prior_report;
  EXPECT_GE(with.summary.floor_points + with.summary.floor_lines, 20);
  EXPECT_NEAR(without.refined_scale, 1 / 1.03, 0.01);  // the error the prior removes
  EXPECT_NEAR(with.refined_scale, 1.0, 0.005);
  // The factor found, the wheel-radius error: lambda is seen only through the 59 per-step priors,
  // whose along-track sigma is 3 % of a step, so it is known to 0.03 / sqrt(59) = 0.004; three of
  // those (observed 0.9759: 0.005 off with the along/across prior, 0.9747 with the isotropic one).
  EXPECT_NEAR(with.summary.odometry_scale, 1 / 1.03, 3 * 0.03 / std::sqrt(59.0));
  EXPECT_LE(with.refined.position_rmse_m, with.odometry.position_rmse_m / 5);
  EXPECT_LE(with.refined.rotation_rpe_rad, with.odometry.rotation_rpe_rad / 2);
  EXPECT_FALSE(without.summary.floor_prior_used);
  EXPECT_GT(without.refined.position_rmse_m, 3 * with.refined.position_rmse_m);
}

// The odometry's rotation bias is estimated (auto) where the floor prior may apply: a ground robot's
// rig and planar odometry, the prior not off (docs/bundle_adjustment.md, "Floor scale bias"). Not
// with the prior off, nor with the camera at the base origin (the VGG and Strecha imports), where
// the problem stays as it was, bit for bit.
TEST(FloorPriorTest, RotationBiasIsEstimatedWhereTheFloorPriorMayApply) {
  const FloorRun with = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto);
  const FloorRun without = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto, {}, /*bias_on_floor=*/false);
  std::printf(
      "[ figures  ] rotation bias on the floor: b_z %.6f rad (odometry drift %.4f rad/frame); scale %.5f "
      "-> %.5f, camera position RMSE %.4f -> %.4f m, odometry scale %.5f -> %.5f\n",
      with.summary.odometry_rotation_bias_rad[2], kSmallDriftRad, without.refined_scale, with.refined_scale,
      without.refined.position_rmse_m, with.refined.position_rmse_m, without.summary.odometry_scale,
      with.summary.odometry_scale);
  EXPECT_TRUE(with.summary.odometry_rotation_bias_estimated);
  EXPECT_FALSE(without.summary.odometry_rotation_bias_estimated);
  EXPECT_NEAR(with.summary.odometry_rotation_bias_rad[2], kSmallDriftRad, kSmallDriftRad / 4);
  const FloorRun off = RunFloorLoop(0, 1.0, FloorPriorMode::kOff);
  EXPECT_FALSE(off.summary.odometry_rotation_bias_estimated);
  const FloorRun no_rig = RunFloorLoop(-1.0, 0.0, FloorPriorMode::kAuto);
  const FloorRun no_rig_without = RunFloorLoop(-1.0, 0.0, FloorPriorMode::kAuto, {}, false);
  EXPECT_FALSE(no_rig.summary.odometry_rotation_bias_estimated);
  ASSERT_EQ(no_rig.world_T_base_refined.size(), no_rig_without.world_T_base_refined.size());
  for (size_t f = 0; f < no_rig.world_T_base_refined.size(); ++f) {
    EXPECT_EQ(no_rig.world_T_base_refined[f].translation, no_rig_without.world_T_base_refined[f].translation);
  }
}

// The line search on the scale: the same 0.5 m lap, odometry 3 % too long and too short, every
// solve stopped at a loose function tolerance (1e-3) so that the joint solves leave part of the
// odometry's error. lambda (1 + error) is the trajectory's length against the truth (1 is right).
// Figures protected: both within 0.004 of 1 (observed 0.99891 / 0.99701) and within 0.003 of each
// other (0.0019). Without the search the solves stop at 1.00068 / 0.99448 (0.0062 apart, the short
// one 0.0055 off): both bounds fail. At 1e-2 the search's samples, which re-solve only the
// landmarks in Ceres's inner iterations, stop after one or two iterations, not converged enough for
// the parabola (0.99604 / 1.00011); at the pipeline's 1e-4 / 1e-6 they are.
TEST(FloorPriorTest, TheScaleLineSearchFindsTheScaleTheSolvesStopShortOf) {
  constexpr double kLooseTolerance = 1e-3;
  auto run = [](double error) {
    const FloorRun result = RunFloorLoop(0, 0.5, FloorPriorMode::kAuto, {}, true, error, kLooseTolerance);
    EXPECT_TRUE(result.summary.floor_prior_used) << result.summary.floor_prior_report;
    EXPECT_NE(result.summary.floor_prior_report.find("scale line search"), std::string::npos)
        << result.summary.floor_prior_report;
    return result.summary.odometry_scale * (1 + error);
  };
  const double long_scale = run(+kScaleError), short_scale = run(-kScaleError);
  std::printf("[ figures  ] 0.5 m camera, function tolerance %g: lambda * (1 + e) with e = +3 %% / -3 %%: "
              "%.5f / %.5f\n",
              kLooseTolerance, long_scale, short_scale);
  EXPECT_NEAR(long_scale, 1.0, 0.004);
  EXPECT_NEAR(short_scale, 1.0, 0.004);
  EXPECT_LE(std::abs(long_scale - short_scale), 0.003);
}

// The start at the floor's scale (docs/bundle_adjustment.md, "Floor prior"), here on the 60-frame
// lap (floor_start_min_frames 0): the coarse solve holds the bases on the floor, so its map stays
// level at the odometry's scale, 3 % too long, and its floor lies at c (1 - 1.03) = -3 cm (c = 1 m,
// the camera's height); the map is scaled about the first camera to put it at z = 0, and the fine
// solves start at lambda = 1 / 1.03 = 0.9709. Figures protected: the plane at -0.03 m to 5 mm
// (observed -0.0276) and the start's lambda 0.9709 to 0.005 (observed 0.9731). With the default
// (400 frames) the lap does not start there.
TEST(FloorPriorTest, TheFineSolvesStartAtTheFloorsScale) {
  const FloorRun run = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto, {}, true, kScaleError, 0, 0);
  const std::string& report = run.summary.floor_prior_report;
  const std::string note = "started at odometry scale ";
  const size_t at = report.find(note);
  ASSERT_NE(at, std::string::npos) << report;
  const double start_scale = std::stod(report.substr(at + note.size()));
  std::printf("[ figures  ] floor plane on the coarse map at %.4f m, started at lambda %.4f\n",
              run.summary.floor_plane_z_m.value_or(0), start_scale);
  ASSERT_TRUE(run.summary.floor_plane_z_m.has_value());
  EXPECT_NEAR(*run.summary.floor_plane_z_m, 1.0 * (1 - (1 + kScaleError)), 0.005);
  EXPECT_NEAR(start_scale, 1 / (1 + kScaleError), 0.005);
  const FloorRun short_run = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto);
  EXPECT_EQ(short_run.summary.floor_prior_report.find(note), std::string::npos);
}

// ParabolaMinimumStep on hand values: the vertex of the parabola through (-1, c-), (0, c0), (1, c+),
// clamped to +-max_steps; the lowest sample when the parabola is not convex.
TEST(FloorPriorTest, ParabolaMinimumStepOnHandValues) {
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(1, 0, 1, 2), 0);
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(3, 1, 0, 2), 1.5);     // a = 0.5, b = -1.5
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(0, 1, 3, 2), -1.5);
  EXPECT_NEAR(ParabolaMinimumStep(5, 1, 0, 2), 2.5 / 3, 1e-15);  // a = 1.5, b = -2.5
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(10, 5, 0.1, 2), 2);    // vertex at 49.5, clamped
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(0.1, 5, 10, 2), -2);
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(1, 0.9, 0.7, 2), 1);   // concave: the lowest sample
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(0.5, 1, 1.2, 2), -1);
  EXPECT_DOUBLE_EQ(ParabolaMinimumStep(1, 1, 1, 2), 0);       // flat
}

// Largest |z| (m) and tilt (rad, the angle of the base's z axis from the world's) of a trajectory.
std::pair<double, double> LargestHeightAndTilt(const std::vector<Pose3>& world_T_base) {
  double height = 0, tilt = 0;
  for (const Pose3& pose : world_T_base) {
    height = std::max(height, std::abs(pose.translation.z()));
    const Eigen::Vector3d up = pose.rotation * Eigen::Vector3d::UnitZ();
    tilt = std::max(tilt, std::acos(std::min(1.0, up.z())));
  }
  return {height, tilt};
}

// The base-on-floor prior: the odometry is planar and level, so the rig check passes and every
// base pose is held at z = 0 (sigma 1 cm) and level (sigma 1 cm / 1 m = 0.01 rad). Figures protected
// (observed with the prior, with the rotation bias that auto estimates; without the prior 4.1 mm,
// 1.9 mrad, 0.9976, 8.0 mm, each beyond its bound): the largest base height under 2 mm (0.6 mm),
// the largest tilt under 1.8 mrad (1.3), the refined scale right to 0.2 % (0.9993) and the camera
// positions within 6 mm RMS (2.6 mm).
TEST(FloorPriorTest, BasePosesAreHeldOnTheFloor) {
  const FloorRun with = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto);
  EXPECT_NE(with.summary.floor_prior_report.find("base poses held on it"), std::string::npos)
      << with.summary.floor_prior_report;
  const auto [height_with, tilt_with] = LargestHeightAndTilt(with.world_T_base_refined);
  std::printf("[ figures  ] base poses: largest height %.4f m, largest tilt %.5f rad, scale %.4f\n", height_with,
              tilt_with, with.refined_scale);
  EXPECT_LT(height_with, 0.002);
  EXPECT_LT(tilt_with, 0.0018);
  EXPECT_NEAR(with.refined_scale, 1.0, 0.002);
  EXPECT_LT(with.refined.position_rmse_m, 0.006);
}

// The base origin is not on the floor: the scene's floor 0.5 m below it (the camera 0.5 m above
// the base origin, 1 m above the floor). The plane is found at about -0.5 m, far beyond the
// 0.075 m (3 x 0.03 x 0.5 m + 0.03 m) the noise model allows: auto does not apply it, the same as
// with the prior off, bit for bit (the rotation bias, which auto estimates on this rig whether or
// not a floor is found, left out of both).
TEST(FloorPriorTest, StaysOffWhenTheBaseIsNotOnTheFloor) {
  const FloorRun automatic =
      RunFloorLoop(-0.5, 0.5, FloorPriorMode::kAuto, {}, /*bias_on_floor=*/false);
  const FloorRun off = RunFloorLoop(-0.5, 0.5, FloorPriorMode::kOff);
  EXPECT_FALSE(automatic.summary.floor_prior_used);
  EXPECT_NE(automatic.summary.floor_prior_report.find("not on the floor"), std::string::npos)
      << automatic.summary.floor_prior_report;
  ASSERT_TRUE(automatic.summary.floor_plane_z_m.has_value());  // found, and rejected
  EXPECT_NEAR(*automatic.summary.floor_plane_z_m, -0.5, 0.05);
  EXPECT_EQ(automatic.summary.odometry_scale, 1.0);
  ASSERT_EQ(automatic.world_T_base_refined.size(), off.world_T_base_refined.size());
  for (size_t f = 0; f < off.world_T_base_refined.size(); ++f) {
    EXPECT_EQ(automatic.world_T_base_refined[f].translation, off.world_T_base_refined[f].translation);
  }
}

// A camera at the base origin's height (as the VGG and Strecha imports, whose T_base_camera is the
// identity): the rig check refuses before anything is looked at.
TEST(FloorPriorTest, StaysOffWithTheCameraAtTheBaseOrigin) {
  const FloorRun automatic = RunFloorLoop(-1.0, 0.0, FloorPriorMode::kAuto);
  EXPECT_FALSE(automatic.summary.floor_prior_used);
  EXPECT_FALSE(automatic.summary.floor_plane_z_m.has_value());
  EXPECT_NE(automatic.summary.floor_prior_report.find("above the base origin"), std::string::npos)
      << automatic.summary.floor_prior_report;
  EXPECT_EQ(FloorPriorRigProblem(Pose3::Identity(), {Pose3::Identity()}, 0.01).empty(), false);
}

TEST(FloorPriorTest, RigAndOdometryChecks) {
  const Pose3 rig = testing::RobotCalibration().base_T_camera;
  const Pose3 flat(Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(2, 1, 0));
  EXPECT_EQ(FloorPriorRigProblem(rig, {Pose3::Identity(), flat}, 0.01), "");
  Pose3 raised = flat;
  raised.translation.z() = 0.02;  // 2 sigma off the floor
  EXPECT_NE(FloorPriorRigProblem(rig, {Pose3::Identity(), raised}, 0.01), "");
  // Tilted by 0.02 rad: more than sigma / camera height = 0.01 rad.
  const Pose3 tilted(Eigen::Quaterniond(Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX())), Eigen::Vector3d(1, 0, 0));
  EXPECT_NE(FloorPriorRigProblem(rig, {Pose3::Identity(), tilted}, 0.01), "");
  EXPECT_NE(FloorPriorRigProblem(testing::RobotCalibration(0.2, 0.05).base_T_camera, {flat}, 0.01), "");
}

// The floor is the lowest horizontal slab of at least 10 landmarks: not the (larger) table top
// above it, not a few stray points below it.
TEST(FloorPriorTest, FindsTheLowestSupportedPlane) {
  Landmarks landmarks;
  auto add = [&](double x, double y, double z) {
    landmarks.points.emplace_back();
    landmarks.points.back().position = Eigen::Vector3d(x, y, z);
  };
  for (int i = 0; i < 15; ++i) add(i, 0, -0.02 + 0.002 * (i % 5));  // the floor, 2 cm low
  for (int i = 0; i < 40; ++i) add(i, 1, 0.75);                      // a table
  for (int i = 0; i < 3; ++i) add(i, 2, -0.4);                       // mis-triangulated
  for (int i = 0; i < 20; ++i) add(i, 3, 0.05 * i);                  // spread over the height
  FloorPlane plane = FindFloorPlane(landmarks, 1.0, 0.03, 10);
  ASSERT_TRUE(plane.found) << plane.why;
  EXPECT_NEAR(plane.z_m, -0.016, 0.01);
  // 15 floor points and 1 or 2 of the spread ones in the slab.
  EXPECT_GE(plane.support, 15);
  EXPECT_LE(plane.support, 17);
  const FloorLandmarks selected = SelectFloorLandmarks(landmarks, plane.z_m, 0.03);
  EXPECT_EQ(static_cast<int>(selected.points.size()), plane.support);
  // Too few on the floor: the table is then the lowest plane; with the table gone, nothing.
  landmarks.points.erase(landmarks.points.begin(), landmarks.points.begin() + 10);
  plane = FindFloorPlane(landmarks, 1.0, 0.03, 10);
  ASSERT_TRUE(plane.found);
  EXPECT_NEAR(plane.z_m, 0.75, 0.01);
  landmarks.points.erase(landmarks.points.begin() + 5, landmarks.points.begin() + 45);
  EXPECT_FALSE(FindFloorPlane(landmarks, 1.0, 0.03, 10).found);
}

// Twelve points 0.15 m under the floor (as mis-triangulated landmarks that happen to gather): the
// lowest slab of 10 or more is theirs, beyond the 0.075 m the noise model allows (3 x 0.03 x 1 m +
// 0.03 m), but the floor within it holds more, so the prior is applied to the floor and the scale
// corrected as without them; a slab that outnumbered the floor would still refuse it (the test above).
TEST(FloorPriorTest, AStraySlabUnderTheFloorIsPassedOver) {
  std::vector<Eigen::Vector3d> stray;
  for (int i = 0; i < 12; ++i) stray.emplace_back(-1.5 + 0.25 * i, 2.3 + 0.05 * (i % 3), -0.15);
  const FloorRun run = RunFloorLoop(0, 1.0, FloorPriorMode::kAuto, stray);
  EXPECT_TRUE(run.summary.floor_prior_used) << run.summary.floor_prior_report;
  EXPECT_NE(run.summary.floor_prior_report.find("taken for stray"), std::string::npos)
      << run.summary.floor_prior_report;
  EXPECT_NEAR(run.refined_scale, 1.0, 0.005);
}

// Occlusion candidates (points seen as a T or an X) are not floor landmarks: 12 of them 2 cm above
// a floor of 30 points would lift its median plane and be held at z = 0; marked, they are left out
// of the search and of the selection.
TEST(FloorPriorTest, OcclusionCandidatesAreNotFloorLandmarks) {
  Landmarks landmarks;
  auto add = [&](double x, double z, bool occlusion) {
    landmarks.points.emplace_back();
    landmarks.points.back().position = Eigen::Vector3d(x, 0, z);
    landmarks.points.back().occlusion_candidate = occlusion;
  };
  for (int i = 0; i < 30; ++i) add(i, -0.002 + 0.001 * (i % 5), false);  // the floor, at z = 0
  for (int i = 0; i < 40; ++i) add(i, 0.02, true);                        // T/X "points" above it
  const FloorPlane plane = FindFloorPlane(landmarks, 1.0, 0.03, 10);
  ASSERT_TRUE(plane.found) << plane.why;
  EXPECT_NEAR(plane.z_m, 0.0, 0.002);
  EXPECT_EQ(plane.support, 30);
  const FloorLandmarks selected = SelectFloorLandmarks(landmarks, plane.z_m, 0.03);
  EXPECT_EQ(selected.points.size(), 30u);
  for (int index : selected.points) EXPECT_FALSE(landmarks.points[index].occlusion_candidate);
  // Unmarked, the same 40 would carry the plane up to them.
  for (PointLandmark& point : landmarks.points) point.occlusion_candidate = false;
  EXPECT_GT(FindFloorPlane(landmarks, 1.0, 0.03, 10).z_m, 0.01);
}

// Re-selection on a map the prior has already rescaled (found on a held-out distorted corridor
// with the branch search on: 11 stray landmarks gathered 4 cm under the floor and, searched from
// below again, replaced its 100; the floor scale then went 0.4 % wrong and the ATE ratio from 0.06
// to 0.25). Searched around z = 0, the floor stays; from below, a stray slab 6 cm down is taken.
TEST(FloorPriorTest, ReselectionAroundTheFloorIgnoresAStraySlabBelow) {
  Landmarks landmarks;
  auto add = [&](double x, double y, double z) {
    landmarks.points.emplace_back();
    landmarks.points.back().position = Eigen::Vector3d(x, y, z);
  };
  for (int i = 0; i < 60; ++i) add(i, 0, -0.004 + 0.002 * (i % 5));  // the floor, at z = 0
  for (int i = 0; i < 11; ++i) add(i, 2, -0.065 + 0.001 * i);         // stray, 6 cm below
  const FloorPlane from_below = FindFloorPlane(landmarks, 1.0, 0.03, 10);
  ASSERT_TRUE(from_below.found);
  EXPECT_LT(from_below.z_m, -0.02);  // what the first selection's rule does here
  const FloorPlane around = FindFloorPlane(landmarks, 1.0, 0.03, 10, 0.0);
  ASSERT_TRUE(around.found) << around.why;
  EXPECT_NEAR(around.z_m, 0.0, 0.003);
  EXPECT_GE(around.support, 60);
  // Nothing near the height asked for: not found, with the reason.
  const FloorPlane elsewhere = FindFloorPlane(landmarks, 1.0, 0.03, 10, 0.5);
  EXPECT_FALSE(elsewhere.found);
  EXPECT_NE(elsewhere.why.find("within"), std::string::npos) << elsewhere.why;
}

}  // namespace
}  // namespace sfm
