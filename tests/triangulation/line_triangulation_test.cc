#include "backend/triangulation/line_triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::DistanceToLine;
using testing::ForwardCameras;
using testing::LineAngle;
using testing::LookAt;
using testing::PixelNoise;
using testing::Project;
using testing::TestK;

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180;

// The junction segment from `junction` to `far_end` as each camera sees it.
std::vector<LineView> Observe(const std::vector<Pose3>& cameras, const Eigen::Vector3d& junction,
                              const Eigen::Vector3d& far_end, std::mt19937* random = nullptr,
                              double sigma_px = 0) {
  std::vector<LineView> views;
  for (const Pose3& camera : cameras) {
    LineView view{camera, Project(TestK(), camera, junction), Project(TestK(), camera, far_end)};
    if (random != nullptr) {
      view.p0 += PixelNoise(*random, sigma_px);
      view.p1 += PixelNoise(*random, sigma_px);
    }
    views.push_back(view);
  }
  return views;
}

// A random unit direction whose planes in `cameras` (noise-free) are at least 5 degrees apart:
// a line the views determine. Seeded through Eigen's Random (std::rand).
Eigen::Vector3d RandomObservableDirection(const std::vector<Pose3>& cameras,
                                          const Eigen::Vector3d& junction) {
  for (;;) {
    const Eigen::Vector3d direction = Eigen::Vector3d::Random().normalized();
    std::vector<Eigen::Vector4d> planes;
    for (const LineView& view : Observe(cameras, junction, junction + direction)) {
      planes.push_back(BackProjectedPlane(TestK(), view));
    }
    if (MaxPlaneAngle(planes) > 5 * kRadiansPerDegree) return direction;
  }
}

TEST(LineTriangulationTest, TheBackProjectedPlaneHoldsTheCentreAndTheLine) {
  const Pose3 camera = LookAt(Eigen::Vector3d(1, -0.5, 1.2), Eigen::Vector3d(10, 1, 0));
  const Eigen::Vector3d a(5, 1.5, 0.5), b(5.5, 1, 2.0);
  const Eigen::Vector4d plane =
      BackProjectedPlane(TestK(), {camera, Project(TestK(), camera, a), Project(TestK(), camera, b)});
  EXPECT_NEAR(plane.head<3>().norm(), 1.0, 1e-15);
  for (const Eigen::Vector3d& x : {camera.translation, a, b})
    EXPECT_NEAR(plane.head<3>().dot(x) + plane.w(), 0, 1e-12);
}

TEST(LineTriangulationTest, RecoversALineTo1e9WithoutNoise) {
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Pose3> cameras = ForwardCameras();
    cameras.resize(2 + trial % 4);
    const Eigen::Vector3d junction = Eigen::Vector3d(5, 1.5, 1) + 0.5 * Eigen::Vector3d::Random();
    const Eigen::Vector3d direction = RandomObservableDirection(cameras, junction);
    const Eigen::Vector3d far_end = junction + 1.0 * direction;
    const std::vector<LineView> views = Observe(cameras, junction, far_end);
    Line3 line;
    ASSERT_EQ(TriangulateLine(TestK(), views, LineTriangulationOptions(), &line), LineStatus::kOk);
    EXPECT_LT(LineAngle(line.direction, direction), /*max_rad=*/1e-9);
    EXPECT_LT(DistanceToLine(junction, line.point, line.direction), /*max_m=*/1e-9);
    EXPECT_LT(DistanceToLine(far_end, line.point, line.direction), /*max_m=*/1e-9);
    EXPECT_LT(LineReprojectionError(TestK(), views, line), 1e-9);

    // Bounded by the junction point, or by the back-projected junction locations: the true ends.
    for (const Eigen::Vector3d* junction_point : {&junction, static_cast<const Eigen::Vector3d*>(nullptr)}) {
      Segment3 segment;
      ASSERT_EQ(BoundLine(TestK(), views, line, junction_point, LineTriangulationOptions(), &segment), LineStatus::kOk);
      EXPECT_LT((segment.end0 - junction).norm(), 1e-9);
      EXPECT_LT((segment.end1 - far_end).norm(), 1e-9);
    }
  }
}

// Triangulates `trials` noisy views (sigma_px on both ends in every view) of the segment from
// junction to far_end, each moved by up to 0.2 m; RMS and largest direction error (degrees) and
// distance of the true junction from the line (metres) over the triangulated ones.
struct NoiseFigures {
  int triangulated = 0;
  double rms_angle_deg = 0, max_angle_deg = 0, rms_distance_m = 0, max_distance_m = 0;
};

NoiseFigures MeasureNoise(const std::vector<Pose3>& cameras, const Eigen::Vector3d& junction,
                          const Eigen::Vector3d& far_end, double sigma_px, int trials, std::mt19937* random) {
  NoiseFigures figures;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Vector3d offset = 0.2 * Eigen::Vector3d::Random();
    Line3 line;
    if (TriangulateLine(TestK(), Observe(cameras, junction + offset, far_end + offset, random, sigma_px),
                        LineTriangulationOptions(), &line) != LineStatus::kOk) {
      continue;
    }
    ++figures.triangulated;
    const double angle = LineAngle(line.direction, far_end - junction) / kRadiansPerDegree;
    const double distance = DistanceToLine(junction + offset, line.point, line.direction);
    figures.rms_angle_deg += angle * angle;
    figures.rms_distance_m += distance * distance;
    figures.max_angle_deg = std::max(figures.max_angle_deg, angle);
    figures.max_distance_m = std::max(figures.max_distance_m, distance);
  }
  figures.rms_angle_deg = std::sqrt(figures.rms_angle_deg / figures.triangulated);
  figures.rms_distance_m = std::sqrt(figures.rms_distance_m / figures.triangulated);
  return figures;
}

TEST(LineTriangulationTest, HalfAPixelOfNoiseOnTheEndsGivesStatedErrors) {
  // The five forward views (1.6 m along x), 0.5 px of Gaussian noise per coordinate on both ends
  // in every view, 1000 trials per line, each line moved by up to 0.2 m. The errors grow as the
  // planes' angle shrinks towards min_plane_angle_deg (docs/tracks_and_triangulation.md).
  std::mt19937 random(11);
  const std::vector<Pose3> cameras = ForwardCameras();
  // A door post 5 m ahead, 1.5 m to the left, 1.5 m long: planes about 7 degrees apart.
  // Measured: direction RMS 2.4 degrees (largest 10.9), junction off the line RMS 4.4 cm (15 cm).
  const NoiseFigures post =
      MeasureNoise(cameras, Eigen::Vector3d(5, 1.5, 0.5), Eigen::Vector3d(5, 1.5, 2), 0.5, 1000, &random);
  // A ceiling edge across the path 6 m ahead, 1.2 m above the cameras, 1 m long: planes about 4
  // degrees apart. Measured: direction RMS 8.4 degrees (largest 27.8), junction RMS 10 cm (33 cm).
  const NoiseFigures lintel =
      MeasureNoise(cameras, Eigen::Vector3d(6, 1, 2.2), Eigen::Vector3d(6, 0, 2.2), 0.5, 1000, &random);
  for (const NoiseFigures& figures : {post, lintel}) {
    std::printf(
        "lines, 0.5 px noise: %d of 1000 triangulated, direction RMS %.2f deg (largest %.2f), "
        "junction off the line RMS %.4f m (largest %.4f)\n",
        figures.triangulated, figures.rms_angle_deg, figures.max_angle_deg, figures.rms_distance_m,
        figures.max_distance_m);
  }
  // Stated: post RMS < 3.5 degrees and 6 cm; ceiling edge RMS < 12 degrees and 15 cm; all found.
  EXPECT_EQ(post.triangulated, 1000);
  EXPECT_LT(post.rms_angle_deg, 3.5);
  EXPECT_LT(post.rms_distance_m, 0.06);
  EXPECT_GE(lintel.triangulated, 990);
  EXPECT_LT(lintel.rms_angle_deg, 12);
  EXPECT_LT(lintel.rms_distance_m, 0.15);
}

TEST(LineTriangulationTest, ALineParallelToTheMotionIsUnobservable) {
  // A corridor's wall-floor edge along x; the cameras move along x: every plane is the one holding
  // the edge and the path.
  const std::vector<LineView> views =
      Observe(ForwardCameras(), Eigen::Vector3d(4, 1.5, 0.2), Eigen::Vector3d(6, 1.5, 0.2));
  std::vector<Eigen::Vector4d> planes;
  for (const LineView& view : views) planes.push_back(BackProjectedPlane(TestK(), view));
  EXPECT_LT(MaxPlaneAngle(planes), 1e-9);
  Line3 line;
  EXPECT_EQ(TriangulateLine(TestK(), views, LineTriangulationOptions(), &line), LineStatus::kUnobservable);
}

TEST(LineTriangulationTest, TooFewViewsAndAWrongCorrespondenceAreTold) {
  const std::vector<Pose3> cameras = ForwardCameras();
  const Eigen::Vector3d junction(5, 1.5, 0.5), far_end(5, 1.5, 2);
  Line3 line;
  EXPECT_EQ(
      TriangulateLine(TestK(), Observe({cameras[0]}, junction, far_end), LineTriangulationOptions(), &line),
      LineStatus::kTooFewViews);
  std::vector<LineView> views = Observe(cameras, junction, far_end);
  views[2].p1.x() += 20;  // another segment in one view
  EXPECT_EQ(TriangulateLine(TestK(), views, LineTriangulationOptions(), &line),
            LineStatus::kLargeReprojectionError);
}

TEST(LineTriangulationTest, BoundingRejectsAnEmptyExtentAndEndsBehindACamera) {
  const std::vector<Pose3> cameras = ForwardCameras();
  const Eigen::Vector3d junction(5, 1.5, 0.5), far_end(5, 1.5, 2);
  const std::vector<LineView> views = Observe(cameras, junction, far_end);
  Line3 line;
  ASSERT_EQ(TriangulateLine(TestK(), views, LineTriangulationOptions(), &line), LineStatus::kOk);
  Segment3 segment;
  // A junction point beyond the far end: the views bound nothing between them.
  const Eigen::Vector3d beyond(5, 1.5, 2.5);
  EXPECT_EQ(BoundLine(TestK(), views, line, &beyond, LineTriangulationOptions(), &segment), LineStatus::kNoExtent);

  // A camera past the segment looking the same way sees it from behind.
  std::vector<LineView> with_behind = views;
  const Pose3 past = LookAt(Eigen::Vector3d(7, 0, 1), Eigen::Vector3d(17, 0, 1));
  with_behind.push_back({past, Project(TestK(), past, junction), Project(TestK(), past, far_end)});
  ASSERT_EQ(TriangulateLine(TestK(), with_behind, LineTriangulationOptions(), &line), LineStatus::kOk);
  EXPECT_EQ(BoundLine(TestK(), with_behind, line, &junction, LineTriangulationOptions(), &segment), LineStatus::kBehindCamera);
}

// The robot stands still and the odometry invents up to 1.6 mm of camera motion (the e2e test
// NoMotionWithNoisyOdometryGivesNoLine): six centres within 1.6 mm, the camera turned by up to
// 0.3 degrees, short junction segments (12-20 px) with 0.3 px of noise on both ends. The measured
// planes then differ by noise alone, often by more than 3 degrees; the centres do not spread across
// them (or their intersection passes next to the centres), so no line may come out.
TEST(LineTriangulationTest, NoiseWithoutBaselineGivesNoLine) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int planes_past_threshold = 0, kept = 0, too_close = 0, no_spread = 0;
  const LineTriangulationOptions options;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<Pose3> cameras;
    for (int k = 0; k < 6; ++k) {
      const Eigen::Vector3d centre = Eigen::Vector3d(1, 1, 1) + 0.0008 * Eigen::Vector3d(uniform(random), uniform(random), 0);
      const double yaw = 0.005 * uniform(random);
      cameras.push_back(LookAt(centre, centre + Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0)));
    }
    const Eigen::Vector3d junction =
        Eigen::Vector3d(1, 1, 1) + Eigen::Vector3d(3 + 2 * uniform(random), 1.5 * uniform(random), uniform(random));
    const Eigen::Vector3d direction = Eigen::Vector3d::Random().normalized();
    const double length_px = 16 + 4 * uniform(random);
    const Eigen::Vector3d far_end = junction + direction * (length_px / 450 * (junction.x() - 1));
    const std::vector<LineView> views = Observe(cameras, junction, far_end, &random, 0.3);
    if ((views[0].p1 - views[0].p0).norm() < 8) continue;
    std::vector<Eigen::Vector4d> planes;
    for (const LineView& view : views) planes.push_back(BackProjectedPlane(TestK(), view));
    if (MaxPlaneAngle(planes) > options.min_plane_angle_deg * kRadiansPerDegree) ++planes_past_threshold;
    Line3 line;
    Segment3 segment;
    LineStatus status = TriangulateLine(TestK(), views, options, &line);
    if (status == LineStatus::kOk) status = BoundLine(TestK(), views, line, nullptr, options, &segment);
    if (status == LineStatus::kOk) ++kept;
    if (status == LineStatus::kTooClose) ++too_close;
    if (status == LineStatus::kUnobservable && MaxPlaneAngle(planes) > options.min_plane_angle_deg * kRadiansPerDegree)
      ++no_spread;
  }
  std::printf("no baseline: %d of 2000 tracks had planes more than 3 degrees apart: %d too close, %d without "
              "centre spread, %d kept\n",
              planes_past_threshold, too_close, no_spread, kept);
  EXPECT_GT(planes_past_threshold, 20);  // the plane angle alone would let these through
  EXPECT_EQ(kept, 0);
}

TEST(LineTriangulationTest, TheCentreSpreadIsThePlaneAngleWithoutNoise) {
  const std::vector<Pose3> cameras = ForwardCameras();
  const Eigen::Vector3d junction(5, 1.5, 0.5), far_end(5, 1.5, 2);  // a door post: planes 7 deg apart
  const std::vector<LineView> views = Observe(cameras, junction, far_end);
  std::vector<Eigen::Vector4d> planes;
  std::vector<Eigen::Vector3d> centres;
  for (const LineView& view : views) {
    planes.push_back(BackProjectedPlane(TestK(), view));
    centres.push_back(view.world_T_camera.translation);
  }
  const Line3 truth{junction, (far_end - junction).normalized()};
  EXPECT_NEAR(MaxCentreSpreadAngle(planes, centres, truth), MaxPlaneAngle(planes), 1e-9);
  // Coincident centres: 0, whatever the planes.
  const std::vector<Eigen::Vector3d> one_centre(centres.size(), centres[0]);
  std::vector<Eigen::Vector4d> through_it;
  for (const Eigen::Vector4d& plane : planes) {
    through_it.push_back(plane);
    through_it.back().w() = -plane.head<3>().dot(centres[0]);
  }
  EXPECT_LT(MaxCentreSpreadAngle(through_it, one_centre, truth), 1e-12);
}

TEST(LineTriangulationTest, ALineNearerThanTheDepthFloorIsRejected) {
  // A short edge 8 cm ahead of cameras 1 cm apart (its line 7.6 cm from the first centre): well
  // determined, but nearer than min_depth_m = 0.1 m.
  std::vector<Pose3> cameras;
  for (int k = 0; k < 3; ++k)
    cameras.push_back(LookAt(Eigen::Vector3d(0, 0.01 * k, 1), Eigen::Vector3d(10, 0.01 * k, 1)));
  const Eigen::Vector3d junction(0.08, 0.005, 0.99), far_end(0.09, 0.005, 1.01);
  const std::vector<LineView> views = Observe(cameras, junction, far_end);
  const LineTriangulationOptions options;
  LineTriangulationOptions nearer = options;
  nearer.min_depth_m = 0.05;
  Line3 line;
  EXPECT_EQ(TriangulateLine(TestK(), views, options, &line), LineStatus::kTooClose);
  ASSERT_EQ(TriangulateLine(TestK(), views, nearer, &line), LineStatus::kOk);
  Segment3 segment;
  EXPECT_EQ(BoundLine(TestK(), views, line, &junction, options, &segment), LineStatus::kTooClose);
  EXPECT_EQ(BoundLine(TestK(), views, line, &junction, nearer, &segment), LineStatus::kOk);
}

TEST(LineTriangulationTest, StatusNames) {
  EXPECT_STREQ(LineStatusName(LineStatus::kTooClose), "too_close");
  EXPECT_STREQ(LineStatusName(LineStatus::kOk), "ok");
  EXPECT_STREQ(LineStatusName(LineStatus::kUnobservable), "unobservable");
  EXPECT_STREQ(LineStatusName(LineStatus::kNoExtent), "no_extent");
}

}  // namespace
}  // namespace sfm
