#include "sequences/importers/vgg_importer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "backend/triangulation/point_triangulation.h"
#include "geometry/camera.h"
#include "geometry/epipolar.h"
#include "frontend/sequence/sequence.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

std::string TestName() { return ::testing::UnitTest::GetInstance()->current_test_info()->name(); }

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// A VGG folder of 4 views of a point cloud, written as the real files are: each P with a negative
// overall sign and, when `mirrored`, in a left-handed copy of the world (X_file = -X_world); the
// corners are the points' exact projections, matched by bt.nview-corners.
struct SyntheticVgg {
  Eigen::Matrix3d K;
  std::vector<Pose3> world_T_camera;
};

SyntheticVgg WriteSyntheticVgg(const fs::path& dir, bool mirrored) {
  SyntheticVgg truth;
  truth.K << 250, 0, 160.5, 0, 245, 119.25, 0, 0, 1;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 60; ++i) {
    points.emplace_back(-3 + 0.1 * i, std::sin(i) * 1.5, 8 + 3 * std::cos(0.7 * i));
  }
  std::ofstream p3d(dir / "bt.p3d");
  for (const Eigen::Vector3d& X : points) {
    const Eigen::Vector3d file = mirrored ? Eigen::Vector3d(-X) : X;
    p3d << file.x() << " " << file.y() << " " << file.z() << "\n";
  }
  // Corner tracks as bt.nview-corners has them: each view's corners list the visible points in
  // reverse order (so that corner and point indices differ), exact projections.
  std::vector<std::vector<std::string>> track_rows(points.size(), std::vector<std::string>(4, "*"));
  for (int v = 0; v < 4; ++v) {
    const Pose3 world_T_camera(Eigen::Quaterniond(Eigen::AngleAxisd(0.04 * v, Eigen::Vector3d(0.1, 1, 0.2).normalized())),
                               Eigen::Vector3d(0.2 * v, -0.05 * v, 0.7 * v));
    truth.world_T_camera.push_back(world_T_camera);
    Eigen::Matrix<double, 3, 4> P = -0.01 * truth.K * world_T_camera.Inverse().Matrix3x4();
    if (mirrored) P.leftCols<3>() *= -1;
    char name[32];
    std::snprintf(name, sizeof(name), "bt.%03d", v);
    std::ofstream camera(dir / (std::string(name) + ".P"));
    camera.precision(17);
    for (int r = 0; r < 3; ++r) camera << P(r, 0) << " " << P(r, 1) << " " << P(r, 2) << " " << P(r, 3) << "\n";
    cv::Mat image(240, 320, CV_8UC1);
    cv::randu(image, 0, 255);
    cv::imwrite((dir / (std::string(name) + ".pgm")).string(), image);
    std::ofstream corners(dir / (std::string(name) + ".corners"));
    corners.precision(17);
    int index = 0;
    for (int p = static_cast<int>(points.size()) - 1; p >= 0; --p) {
      const Eigen::Vector3d x = truth.K * (world_T_camera.Inverse() * points[p]);
      if (x.z() <= 0) continue;
      corners << x.x() / x.z() << " " << x.y() / x.z() << "\n";
      track_rows[p][v] = std::to_string(index++);
    }
  }
  std::ofstream tracks(dir / "bt.nview-corners");
  for (const std::vector<std::string>& row : track_rows) {
    for (const std::string& field : row) tracks << field << "  ";
    tracks << "\n";
  }
  return truth;
}

// Both refits recover poses that are exact for the files' one K (1e-6 units, 1e-6 rad).
void ExpectRecoversTruth(bool mirrored, VggRefit refit) {
  const fs::path dir = testing::MakeScratchDir("vgg_" + TestName());
  const SyntheticVgg truth = WriteSyntheticVgg(dir, mirrored);
  ImportedSequence sequence;
  VggImportSummary summary;
  VggImportOptions options;
  options.refit = refit;
  ASSERT_TRUE(ReadVggSequence(dir.string(), options, &sequence, &summary).ok());
  EXPECT_EQ(summary.joint_refit.has_value(), refit == VggRefit::kJoint);
  if (summary.joint_refit) {
    EXPECT_LT(summary.joint_refit->median_px, 1e-6);
    EXPECT_EQ(summary.joint_refit->observations, 4 * 60);
  }
  EXPECT_EQ(summary.world_mirrored, mirrored);
  EXPECT_LT((summary.K - truth.K).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(sequence.camera.width, 320);
  EXPECT_EQ(sequence.camera.height, 240);
  ASSERT_EQ(sequence.frames.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(sequence.frames[i].timestamp, 0.1 * i);
    EXPECT_LT((sequence.frames[i].world_T_camera.translation - truth.world_T_camera[i].translation).norm(), 1e-6);
    EXPECT_LT(RotationAngle(sequence.frames[i].world_T_camera.rotation, truth.world_T_camera[i].rotation), 1e-6);
    EXPECT_LT(summary.refit_rms_px[i], 1e-6);
  }
}

TEST(VggImporterTest, RecoversPosesFromMirroredFiles) {
  ExpectRecoversTruth(/*mirrored=*/true, VggRefit::kJoint);
}

TEST(VggImporterTest, RecoversPosesFromRightHandedFiles) {
  ExpectRecoversTruth(/*mirrored=*/false, VggRefit::kJoint);
}

TEST(VggImporterTest, PnpRefitRecoversPosesFromMirroredFiles) {
  ExpectRecoversTruth(/*mirrored=*/true, VggRefit::kPnpMedianK);
}

// Each bad input: a one-line error naming the file.
void ExpectError(const fs::path& dir, const std::string& file, const std::string& problem) {
  ImportedSequence sequence;
  VggImportSummary summary;
  const Status status = ReadVggSequence(dir.string(), VggImportOptions(), &sequence, &summary);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(file));
  EXPECT_THAT(status.message(), HasSubstr(problem));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
}

TEST(VggImporterTest, BadInputsGiveOneLineErrors) {
  const fs::path dir = testing::MakeScratchDir("vgg_bad");
  ExpectError(dir / "absent", "absent", "input directory does not exist");
  ExpectError(dir, dir.string(), "no VGG camera files");

  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.002.P") << "1 2 3 4\n5 6 7 8\n9 10 11\n";
  ExpectError(dir, "bt.002.P", "expected 12 numbers (a 3x4 camera matrix), found 11");
  std::ofstream(dir / "bt.002.P") << "1 2 3 4\n5 6 abc 8\n9 10 11 12\n";
  ExpectError(dir, "bt.002.P:2", "'abc' is not a finite number");
  std::ofstream(dir / "bt.002.P") << "1 2 3 4\n2 4 6 8\n9 10 11 12\n";
  ExpectError(dir, "bt.002.P", "singular");

  WriteSyntheticVgg(dir, true);
  fs::remove(dir / "bt.001.pgm");
  ExpectError(dir, "bt.001.pgm", "image file for bt.001.P does not exist");

  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.p3d") << "1 2 3\n4 5\n";
  ExpectError(dir, "bt.p3d", "expected 'X Y Z' per line");
  fs::remove(dir / "bt.p3d");
  ExpectError(dir, "bt.p3d", "file does not exist");

  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.000.pgm") << "P5 not an image";
  ExpectError(dir, "bt.000.pgm", "cannot decode image");

  // The joint refit's inputs.
  // Without the corner tracks the import keeps the PnP truth and says so (a data set without them
  // is still imported).
  WriteSyntheticVgg(dir, true);
  fs::remove(dir / "bt.nview-corners");
  {
    ImportedSequence without_tracks;
    VggImportSummary without_tracks_summary;
    ASSERT_TRUE(ReadVggSequence(dir.string(), VggImportOptions(), &without_tracks, &without_tracks_summary).ok());
    EXPECT_FALSE(without_tracks_summary.joint_refit.has_value());
    bool noted = false;
    for (const std::string& note : without_tracks.notes) noted |= note.find("no joint refit (bt.nview-corners missing)") != std::string::npos;
    EXPECT_TRUE(noted);
  }
  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.002.corners") << "1 2\n3\n";
  ExpectError(dir, "bt.002.corners", "expected 'x y' per line");
  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.nview-corners", std::ios::app) << "1 2 3\n";
  ExpectError(dir, "bt.nview-corners:61", "expected one entry per view (4), found 3");
  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.nview-corners", std::ios::app) << "1 2 3 4\n";
  ExpectError(dir, "bt.nview-corners:61", "more rows than 3D points (60)");
  WriteSyntheticVgg(dir, true);
  std::ofstream(dir / "bt.nview-corners") << "0 x * *\n";
  ExpectError(dir, "bt.nview-corners:1", "'x' is neither a corner index nor '*'");
  std::ofstream(dir / "bt.nview-corners") << "0 999 * *\n";
  ExpectError(dir, "bt.nview-corners:1", "corner 999 of view 1 does not exist");
  std::ofstream(dir / "bt.nview-corners") << "0 1 * *\n";
  ExpectError(dir, "bt.nview-corners", "1 rows for 60 3D points");
  // The plumb-line k1 (on by default) needs the segments: without them k1 stays 0 and the notes
  // say why; it is not combined with a given k1.
  WriteSyntheticVgg(dir, true);
  VggImportOptions from_lines;
  from_lines.k1_from_lines = true;
  ImportedSequence imported;
  VggImportSummary imported_summary;
  Status status = ReadVggSequence(dir.string(), from_lines, &imported, &imported_summary);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_FALSE(imported_summary.plumb_line.has_value());
  EXPECT_EQ(imported.camera.distortion[0], 0);
  bool noted = false;
  for (const std::string& note : imported.notes) {
    noted |= note.find("no plumb-line k1 (") != std::string::npos && note.find("bt.000.lines does not exist") != std::string::npos;
  }
  EXPECT_TRUE(noted);
  from_lines.k1 = -0.05;
  status = ReadVggSequence(dir.string(), from_lines, &imported, &imported_summary);
  EXPECT_THAT(status.message(), HasSubstr("a k1 given and k1 from the lines: choose one"));
  // Not needed by the PnP refit.
  VggImportOptions pnp;
  pnp.refit = VggRefit::kPnpMedianK;
  ImportedSequence sequence;
  VggImportSummary summary;
  EXPECT_TRUE(ReadVggSequence(dir.string(), pnp, &sequence, &summary).ok());
}

TEST(VggImporterTest, UndecodableImageLeavesNoOutput) {
  const fs::path dir = testing::MakeScratchDir("vgg_undecodable");
  fs::create_directories(dir / "in");
  WriteSyntheticVgg(dir / "in", true);
  std::ofstream(dir / "in" / "bt.002.pgm") << "P5\n320 240\n255\ntruncated";
  ImportedSequence sequence;
  VggImportSummary summary;
  ASSERT_TRUE(ReadVggSequence((dir / "in").string(), VggImportOptions(), &sequence, &summary).ok());
  const Status status = WriteImportedSequence(sequence, SequenceWriteOptions(), (dir / "out").string());
  EXPECT_THAT(status.message(), HasSubstr("bt.002.pgm: cannot decode image"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr("importing"))) << "temporary directory left";
  }
}

// --- The real Corridor data --------------------------------------------------------------------

// Rows of whitespace-separated fields; '*' (not seen in that view) becomes -1.
std::vector<std::vector<double>> ReadRows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<double> row;
    std::string field;
    while (fields >> field) row.push_back(field == "*" ? -1 : std::stod(field));
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

// The corridor's matched corners: per view, the corners of bt.NNN.corners; per 3D point (a row of
// bt.p3d), its corner index per view or -1.
struct CorridorCorners {
  std::vector<std::vector<double>> points;  // bt.p3d rows, the files' frame
  std::vector<std::vector<double>> tracks;  // bt.nview-corners
  std::vector<std::vector<std::vector<double>>> corners;

  Eigen::Vector2d Corner(size_t point, int view) const {
    const std::vector<double>& c = corners[view][static_cast<size_t>(tracks[point][view])];
    return Eigen::Vector2d(c[0], c[1]);
  }
};

CorridorCorners ReadCorridorCorners(const std::string& data) {
  CorridorCorners files;
  files.points = ReadRows(fs::path(data) / "bt.p3d");
  files.tracks = ReadRows(fs::path(data) / "bt.nview-corners");
  files.corners.resize(11);
  for (int v = 0; v < 11; ++v) {
    char name[32];
    std::snprintf(name, sizeof(name), "bt.%03d.corners", v);
    files.corners[v] = ReadRows(fs::path(data) / name);
  }
  return files;
}

struct CorridorTruthFigures {
  std::vector<double> view_median_px;
  double median_px = 0;
  double epipolar_truth_px = 0, epipolar_odometry_px = 0;
  std::vector<Eigen::Vector3d> centres;  // the true camera centres, as written
};

// The corridor's ground truth checked the way a user would: import with `options`, read back with
// ReadSequence, project the 3D points with the sequence's K and true poses, and compare with the
// matched Harris corners (bt.nview-corners). The points are bt.p3d's for the PnP refit (which keeps
// them) and the refit's own for the joint refit (which moves them with the poses). Also the
// epipolar distance of consecutive views' corner matches with F from the true poses (what the
// matching is evaluated against) and from the simulated odometry, which needs no 3D point at all.
void MeasureCorridorTruth(const std::string& data, const VggImportOptions& options,
                          CorridorTruthFigures* figures) {
  const fs::path out = fs::path(testing::MakeScratchDir("vgg_corridor_" + TestName())) / "sequence";
  ImportedSequence imported;
  VggImportSummary summary;
  ASSERT_TRUE(ReadVggSequence(data, options, &imported, &summary).ok());
  ASSERT_TRUE(WriteImportedSequence(imported, SequenceWriteOptions(), out.string()).ok());
  EXPECT_TRUE(summary.world_mirrored);  // the corridor's files are left-handed
  Sequence sequence;
  const Status read = ReadSequence(out.string(), &sequence);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(sequence.frames.size(), 11u);
  ASSERT_TRUE(sequence.has_groundtruth);
  const Eigen::Matrix3d K = sequence.calibration.camera.K();
  const CorridorCorners files = ReadCorridorCorners(data);
  std::vector<double> all;
  for (int v = 0; v < 11; ++v) {
    const Pose3 camera_T_world = sequence.frames[v].world_T_base_groundtruth->Inverse();
    figures->centres.push_back(sequence.frames[v].world_T_base_groundtruth->translation);
    std::vector<double> errors;
    for (size_t p = 0; p < files.tracks.size(); ++p) {
      if (files.tracks[p][v] < 0) continue;
      const Eigen::Vector3d X =
          summary.joint_refit
              ? summary.joint_refit->points[p]
              : VggFileToWorld(Eigen::Vector3d(files.points[p][0], files.points[p][1], files.points[p][2]),
                               summary.world_mirrored);
      const Eigen::Vector3d X_camera = camera_T_world * X;
      ASSERT_GT(X_camera.z(), 0) << "point " << p << " behind camera " << v;
      // The corners are in the stored image's pixels: project through the sequence's distortion.
      errors.push_back((sequence.calibration.camera.Project(X_camera) - files.Corner(p, v)).norm());
    }
    std::cout << "[ figure   ] view " << v << ": median reprojection error " << Median(errors) << " px over "
              << errors.size() << " corners\n";
    figures->view_median_px.push_back(Median(errors));
    all.insert(all.end(), errors.begin(), errors.end());
  }
  figures->median_px = Median(all);
  std::cout << "[ figure   ] all views: median reprojection error " << Median(all) << " px over "
            << all.size() << " observations\n";

  std::vector<double> truth_distances, odometry_distances;
  for (int v = 0; v + 1 < 11; ++v) {
    const Frame& a = sequence.frames[v];
    const Frame& b = sequence.frames[v + 1];
    const Eigen::Matrix3d F_truth = FundamentalFromPoses(K, *a.world_T_base_groundtruth, *b.world_T_base_groundtruth);
    const Eigen::Matrix3d F_odometry = FundamentalFromPoses(K, a.world_T_base_odometry, b.world_T_base_odometry);
    for (size_t p = 0; p < files.tracks.size(); ++p) {
      if (files.tracks[p][v] < 0 || files.tracks[p][v + 1] < 0) continue;
      // F acts on undistorted pixels.
      const Eigen::Vector2d ca = sequence.calibration.camera.UndistortPixel(files.Corner(p, v));
      const Eigen::Vector2d cb = sequence.calibration.camera.UndistortPixel(files.Corner(p, v + 1));
      truth_distances.push_back(SymmetricEpipolarDistance(F_truth, {ca.x(), ca.y()}, {cb.x(), cb.y()}));
      odometry_distances.push_back(SymmetricEpipolarDistance(F_odometry, {ca.x(), ca.y()}, {cb.x(), cb.y()}));
    }
  }
  figures->epipolar_truth_px = Median(truth_distances);
  figures->epipolar_odometry_px = Median(odometry_distances);
  std::cout << "[ figure   ] consecutive corner matches: median epipolar distance " << Median(truth_distances)
            << " px (true poses), " << Median(odometry_distances) << " px (odometry)\n";
  EXPECT_GT(Median(odometry_distances), Median(truth_distances));  // the odometry noise shows

  const Eigen::Vector3d drift =
      sequence.frames.back().world_T_base_odometry.translation - sequence.frames.back().world_T_base_groundtruth->translation;
  std::cout << "[ figure   ] odometry end-point drift " << drift.norm() << " units over a "
            << (figures->centres.back() - figures->centres.front()).norm()
            << "-unit first-to-last distance\n";
  EXPECT_EQ(sequence.frames.front().world_T_base_odometry.translation,
            sequence.frames.front().world_T_base_groundtruth->translation);
}

// The PnP refit (--vgg_refit=pnp): the K of the P matrices varies by 5% in focal length and 87 px
// in cx, and each pose is fitted alone onto the fixed bt.p3d for the median K, so the truth misses
// the corners: measured median 1.15 px, per view 0.66..2.57 px (0.28 px with each P's own K).
TEST(VggImporterTest, CorridorPnpTruthReprojectsOntoTheCorners) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  VggImportOptions options;
  options.refit = VggRefit::kPnpMedianK;
  CorridorTruthFigures figures;
  MeasureCorridorTruth(data, options, &figures);
  for (int v = 0; v < 11; ++v) EXPECT_LT(figures.view_median_px[v], 3.0) << "view " << v;
  EXPECT_LT(figures.median_px, 1.5);          // measured 1.15 px
  EXPECT_LT(figures.epipolar_truth_px, 1.0);  // measured 0.27 px
}

// The joint refit (the default): poses and points fitted together to the corners for the median K,
// with the plumb-line k1 (-0.0612, also a default) held and the corners projected through it.
// Measured median 0.292 px, per view 0.23..0.40 px (without k1: 0.341, per view 0.27..0.48; the P
// files with their own K: 0.28 px, the PnP truth 1.15 px); bound 0.4 px overall and 0.6 px per view. The camera centres stay in the files'
// frame and units: after the gauge's similarity they lie 0.009..0.061 units (bound 0.1) from the
// P files' own centres, on a first-to-last distance of 8.71 units (bound: within 1 %).
TEST(VggImporterTest, CorridorJointRefitTruthReprojectsOntoTheCorners) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  CorridorTruthFigures figures;
  MeasureCorridorTruth(data, VggImportOptions(), &figures);
  for (int v = 0; v < 11; ++v) EXPECT_LT(figures.view_median_px[v], 0.6) << "view " << v;
  EXPECT_LT(figures.median_px, 0.4);
  EXPECT_LT(figures.epipolar_truth_px, 0.5);

  // The gauge, against the P files' centres (the null vectors of P, in the sequence's world).
  double largest_offset = 0;
  for (int v = 0; v < 11; ++v) {
    char name[32];
    std::snprintf(name, sizeof(name), "bt.%03d.P", v);
    const std::vector<std::vector<double>> rows = ReadRows(fs::path(data) / name);
    Eigen::Matrix<double, 3, 4> P;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) P(r, c) = rows[r][c];
    }
    // The null vector of P, in the files' frame; the sequence's world is its point reflection.
    const Eigen::Vector3d file_centre = -P.leftCols<3>().inverse() * P.col(3);
    largest_offset =
        std::max(largest_offset, (figures.centres[v] - VggFileToWorld(file_centre, true)).norm());
  }
  std::cout << "[ figure   ] true centres at most " << largest_offset << " units from the P files' centres\n";
  EXPECT_LT(largest_offset, 0.1);
  EXPECT_NEAR((figures.centres.back() - figures.centres.front()).norm(), 8.71, 0.087);
}

// Cross-validation of the camera model on the data set's own measurements (no back-end figure):
// the refit sees the tracks of the even rows of bt.nview-corners only; each odd row is then
// triangulated with the refit's cameras (DLT and Gauss-Newton, K fixed) and its reprojection error
// measured. Same for the PnP truth's cameras (median K), whose held-out points are triangulated
// afresh too (so this is not the 1.15 px of bt.p3d). Measured, median px training / held-out:
// K held (the default) 0.332 / 0.360; cx cy free 0.246 / 0.270 (cy 169: 82 px below every P's);
// k1 free 0.237 / 0.248 (k1 -0.19); fx fy free 0.193 / 0.213 (fx 718, fy 1101); K and k1 free
// 0.190 / 0.207; PnP truth held-out 0.453. Every freed parameter predicts the held-out corners
// better, so this test does not reject them; they are held for what they become (docs/importers.md).
// Bounds: the default's held-out error below 0.4 px, within 10 % of its training error, and below
// the PnP truth's.
TEST(VggImporterTest, CorridorHeldOutCornersJudgeTheCameraModel) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  VggImportOptions pnp;
  pnp.refit = VggRefit::kPnpMedianK;
  ImportedSequence imported;
  VggImportSummary summary;
  ASSERT_TRUE(ReadVggSequence(data, pnp, &imported, &summary).ok());
  std::vector<Pose3> start_poses;
  std::vector<Eigen::Vector3d> start_centres;
  for (const ImportedFrame& frame : imported.frames) {
    start_poses.push_back(frame.world_T_camera.Inverse());
    start_centres.push_back(frame.world_T_camera.translation);
  }
  const CorridorCorners files = ReadCorridorCorners(data);
  std::vector<Eigen::Vector3d> points;
  std::vector<RefitObservation> training;
  for (size_t p = 0; p < files.points.size(); ++p) {
    points.push_back(
        VggFileToWorld(Eigen::Vector3d(files.points[p][0], files.points[p][1], files.points[p][2]), true));
    for (int v = 0; v < 11; ++v) {
      if (p % 2 == 0 && files.tracks[p][v] >= 0)
        training.push_back({v, static_cast<int>(p), files.Corner(p, v)});
    }
  }
  // Held-out median reprojection error of the odd rows for a camera (K, k1) and poses.
  auto held_out_px = [&](const Eigen::Matrix3d& K, double k1, const std::vector<Pose3>& camera_T_world) {
    Camera camera;
    camera.fx = K(0, 0);
    camera.fy = K(1, 1);
    camera.cx = K(0, 2);
    camera.cy = K(1, 2);
    camera.distortion[0] = k1;
    std::vector<double> errors;
    for (size_t p = 1; p < files.points.size(); p += 2) {
      std::vector<PointView> views;
      std::vector<int> view_index;
      for (int v = 0; v < 11; ++v) {
        if (files.tracks[p][v] < 0) continue;
        views.push_back({camera_T_world[v].Inverse(), camera.UndistortPixel(files.Corner(p, v))});
        view_index.push_back(v);
      }
      if (views.size() < 2) continue;
      const Eigen::Vector4d X = TriangulateDlt(K, views);
      bool in_front = X.w() != 0;
      for (size_t i = 0; in_front && i < views.size(); ++i) {
        in_front = (camera_T_world[view_index[i]] * X.hnormalized()).z() > 0;
      }
      if (!in_front) continue;
      const Eigen::Vector3d refined = RefinePoint(K, views, X.hnormalized(), 20);
      for (int v : view_index) {
        errors.push_back((ProjectWithRadial(K, k1, camera_T_world[v] * refined) - files.Corner(p, v)).norm());
      }
    }
    return Median(errors);
  };
  const double pnp_held_out = held_out_px(summary.K, 0, start_poses);
  std::cout << "[ figure   ] PnP truth: held-out median reprojection error " << pnp_held_out << " px\n";

  struct Model {
    const char* name;
    bool focal, principal_point, k1;
  };
  double default_training = 0, default_held_out = 0;
  for (const Model& model :
       {Model{"K held (default)", false, false, false}, Model{"cx cy free", false, true, false},
        Model{"k1 free", false, false, true}, Model{"cx cy k1 free", false, true, true},
        Model{"fx fy free", true, false, false}, Model{"K free", true, true, false},
        Model{"K and k1 free", true, true, true}}) {
    SharedCameraRefitOptions options;
    options.refine_focal = model.focal;
    options.refine_principal_point = model.principal_point;
    options.radial_k1 = model.k1;
    SharedCameraRefit refit;
    ASSERT_TRUE(
        RefitSharedCamera(summary.K, start_poses, points, training, start_centres, options, &refit).ok());
    const double held_out = held_out_px(refit.K, refit.k1, refit.camera_T_world);
    std::cout << "[ figure   ] " << model.name << ": training " << refit.median_px << " px, held-out "
              << held_out << " px; fx " << refit.K(0, 0) << " fy " << refit.K(1, 1) << " cx " << refit.K(0, 2)
              << " cy " << refit.K(1, 2) << " k1 " << refit.k1 << "\n";
    if (!model.focal && !model.principal_point && !model.k1) {
      default_training = refit.median_px;
      default_held_out = held_out;
    }
  }
  EXPECT_LT(default_held_out, 0.4);
  EXPECT_LT(default_held_out, 1.1 * default_training);
  EXPECT_LT(default_held_out, pnp_held_out);
}

// image_warps.txt through the library's reader (failing the test on a read error).
std::vector<Eigen::Matrix<double, 2, 3>> Warps(const fs::path& path) {
  std::vector<Eigen::Matrix<double, 2, 3>> warps;
  const Status read = ReadImageWarps(path.string(), &warps);
  EXPECT_TRUE(read.ok()) << read.message();
  return warps;
}

// With --vgg_warp_to_shared_k the images are resampled to the one K and the poses are each P's
// own: the truth then reprojects onto the matched corners (mapped by image_warps.txt) as well as
// the P files themselves do (0.28 px median), where the default refit leaves 1.15 px.
TEST(VggImporterTest, CorridorWarpedToTheSharedKReprojectsAsTheFilesDo) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  const fs::path out = fs::path(testing::MakeScratchDir("vgg_corridor_warped")) / "sequence";
  VggImportOptions options;
  options.warp_to_shared_k = true;
  ImportedSequence imported;
  VggImportSummary summary;
  ASSERT_TRUE(ReadVggSequence(data, options, &imported, &summary).ok());
  ASSERT_TRUE(WriteImportedSequence(imported, SequenceWriteOptions(), out.string()).ok());
  Sequence sequence;
  const Status read = ReadSequence(out.string(), &sequence);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(sequence.frames.size(), 11u);
  const Camera& camera = sequence.calibration.camera;
  EXPECT_LT(camera.width, 512);  // cropped to what every warped frame covers
  EXPECT_GT(camera.width * camera.height, 512 * 512 / 2);
  const cv::Mat first = cv::imread((out / "images" / "000000.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(first.cols, camera.width);
  EXPECT_EQ(first.rows, camera.height);
  const std::vector<Eigen::Matrix<double, 2, 3>> warps = Warps(out / "image_warps.txt");
  ASSERT_EQ(warps.size(), 11u);

  const Eigen::Matrix3d K = camera.K();
  const std::vector<std::vector<double>> points = ReadRows(fs::path(data) / "bt.p3d");
  const std::vector<std::vector<double>> tracks = ReadRows(fs::path(data) / "bt.nview-corners");
  std::vector<double> all;
  for (int v = 0; v < 11; ++v) {
    char name[32];
    std::snprintf(name, sizeof(name), "bt.%03d.corners", v);
    const std::vector<std::vector<double>> corners = ReadRows(fs::path(data) / name);
    const Pose3 camera_T_world = sequence.frames[v].world_T_base_groundtruth->Inverse();
    std::vector<double> errors;
    for (size_t p = 0; p < tracks.size(); ++p) {
      if (tracks[p][v] < 0) continue;
      const Eigen::Vector3d X =
          VggFileToWorld(Eigen::Vector3d(points[p][0], points[p][1], points[p][2]), summary.world_mirrored);
      const std::vector<double>& corner = corners[static_cast<size_t>(tracks[p][v])];
      const Eigen::Vector2d mapped = warps[v] * Eigen::Vector3d(corner[0], corner[1], 1);
      errors.push_back(((K * (camera_T_world * X)).hnormalized() - mapped).norm());
    }
    EXPECT_LT(Median(errors), 0.6) << "view " << v;  // the P files' own: 0.2..0.4 px per view
    // The images are warped by the same maps: OpenCV's sub-pixel corner search finds a corner of the
    // written image where the map puts the one it finds in the data set's image.
    char image_name[32];
    std::snprintf(image_name, sizeof(image_name), "%06d.png", v);
    const cv::Mat image = cv::imread((out / "images" / image_name).string(), cv::IMREAD_GRAYSCALE);
    std::snprintf(image_name, sizeof(image_name), "bt.%03d.pgm", v);
    const cv::Mat source = cv::imread((fs::path(data) / image_name).string(), cv::IMREAD_GRAYSCALE);
    std::vector<cv::Point2f> in_source, in_image;
    for (const std::vector<double>& corner : corners) {
      const Eigen::Vector2d mapped = warps[v] * Eigen::Vector3d(corner[0], corner[1], 1);
      if (mapped.minCoeff() > 8 && mapped.x() < image.cols - 8 && mapped.y() < image.rows - 8) {
        in_source.emplace_back(static_cast<float>(corner[0]), static_cast<float>(corner[1]));
        in_image.emplace_back(static_cast<float>(mapped.x()), static_cast<float>(mapped.y()));
      }
    }
    const cv::TermCriteria criteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.01);
    cv::cornerSubPix(source, in_source, cv::Size(3, 3), cv::Size(-1, -1), criteria);
    cv::cornerSubPix(image, in_image, cv::Size(3, 3), cv::Size(-1, -1), criteria);
    std::vector<double> distances;
    for (size_t k = 0; k < in_source.size(); ++k) {
      const Eigen::Vector2d mapped = warps[v] * Eigen::Vector3d(in_source[k].x, in_source[k].y, 1);
      distances.push_back((mapped - Eigen::Vector2d(in_image[k].x, in_image[k].y)).norm());
    }
    std::cout << "[ figure   ] view " << v << ": sub-pixel corners of the written image " << Median(distances)
              << " px (median of " << distances.size() << ") from the mapped ones of the data set's image\n";
    EXPECT_LT(Median(distances), 0.2) << "view " << v;
    all.insert(all.end(), errors.begin(), errors.end());
  }
  std::cout << "[ figure   ] warped to the shared K: median reprojection error " << Median(all) << " px over "
            << all.size() << " observations\n";
  EXPECT_LT(Median(all), 0.4);  // measured 0.28 px (the P files: 0.28); 1.15 px with the refit
}

}  // namespace
}  // namespace sfm
