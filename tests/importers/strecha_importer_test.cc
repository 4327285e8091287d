#include "sequences/importers/strecha_importer.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "geometry/epipolar.h"
#include "frontend/sequence/sequence.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// entry-P10's 0000.jpg.camera, shrunk to a 64x48 image so tests can write matching images.
constexpr char kCameraText[] =
    "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n"
    "0.899106 0.0785584 0.430625\n0.437661 -0.17907 -0.881128\n0.00789185 0.980695 -0.195384\n"
    "-4.11244 -2.19149 0.221573\n64 48\n";

void WriteText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// A two-camera Strecha folder with small JPEG images.
fs::path WriteStrechaFolder(const std::string& name) {
  const fs::path dir = testing::MakeScratchDir(name);
  fs::create_directories(dir / "images");
  fs::create_directories(dir / "gt_dense_cameras");
  for (const char* image : {"0000.jpg", "0001.jpg"}) {
    cv::Mat pixels(48, 64, CV_8UC3);
    cv::randu(pixels, 0, 255);
    cv::imwrite((dir / "images" / image).string(), pixels);
    WriteText(dir / "gt_dense_cameras" / (std::string(image) + ".camera"), kCameraText);
  }
  return dir;
}

TEST(StrechaImporterTest, CameraFileGivesKAndPoseWithTheStatedProjection) {
  const fs::path dir = WriteStrechaFolder("strecha_camera");
  StrechaCamera camera;
  ASSERT_TRUE(ReadStrechaCamera((dir / "gt_dense_cameras" / "0000.jpg.camera").string(), &camera).ok());
  EXPECT_EQ(camera.camera.width, 64);
  EXPECT_EQ(camera.camera.height, 48);
  EXPECT_EQ(camera.camera.fx, 57.5);
  EXPECT_EQ(camera.camera.cy, 20.9);
  Eigen::Matrix3d R;
  R << 0.899106, 0.0785584, 0.430625, 0.437661, -0.17907, -0.881128, 0.00789185, 0.980695, -0.195384;
  const Eigen::Vector3d C(-4.11244, -2.19149, 0.221573);
  // x ~ K R^T (X - C) for a point in front of the camera, against the imported pose.
  const Eigen::Vector3d X = C + R * Eigen::Vector3d(0.3, -0.2, 5.0);
  const Eigen::Vector2d expected = (camera.camera.K() * R.transpose() * (X - C)).hnormalized();
  const Eigen::Vector2d imported = camera.camera.ProjectUndistorted(camera.world_T_camera.Inverse() * X);
  EXPECT_LT((imported - expected).norm(), 1e-4);  // R is given to 6 digits and made orthonormal
  EXPECT_LT((camera.world_T_camera.translation - C).norm(), 1e-15);
}

TEST(StrechaImporterTest, ReadsFolderInNameOrder) {
  const fs::path dir = WriteStrechaFolder("strecha_folder");
  ImportedSequence sequence;
  ASSERT_TRUE(ReadStrechaSequence(dir.string(), &sequence).ok());
  ASSERT_EQ(sequence.frames.size(), 2u);
  EXPECT_THAT(sequence.frames[1].source_image, HasSubstr("0001.jpg"));
  EXPECT_DOUBLE_EQ(sequence.frames[1].timestamp, 0.1);
}

void ExpectError(const fs::path& dir, const std::string& file, const std::string& problem) {
  ImportedSequence sequence;
  const Status status = ReadStrechaSequence(dir.string(), &sequence);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(file));
  EXPECT_THAT(status.message(), HasSubstr(problem));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
}

TEST(StrechaImporterTest, BadInputsGiveOneLineErrors) {
  const fs::path dir = WriteStrechaFolder("strecha_bad");
  const fs::path camera = dir / "gt_dense_cameras" / "0001.jpg.camera";
  ExpectError(dir / "absent", "absent", "input directory does not exist");

  WriteText(camera, "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n64\n");
  ExpectError(dir, "0001.jpg.camera", "expected 26 numbers");
  WriteText(camera, "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 zero\n64 48\n");
  ExpectError(dir, "0001.jpg.camera:8", "'zero' is not a finite number");
  WriteText(camera, "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 -1\n0 0 0\n64 48\n");
  ExpectError(dir, "0001.jpg.camera", "R is not a rotation");
  WriteText(camera, "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0.1 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n64 48\n");
  ExpectError(dir, "0001.jpg.camera", "nonzero distortion");
  WriteText(camera, "57.5 0.5 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n64 48\n");
  ExpectError(dir, "0001.jpg.camera", "K must have the form");
  WriteText(camera, "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n64.5 48\n");
  ExpectError(dir, "0001.jpg.camera", "whole pixels");
  WriteText(camera, "58 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n64 48\n");
  ExpectError(dir, "0001.jpg.camera", "K or image size differs from 0000.jpg.camera's");

  WriteText(camera, kCameraText);
  fs::remove(dir / "images" / "0001.jpg");
  ExpectError(dir, "0001.jpg", "image file for 0001.jpg.camera does not exist");
  fs::remove_all(dir / "gt_dense_cameras");
  ExpectError(dir, "gt_dense_cameras", "camera folder does not exist");
}

TEST(StrechaImporterTest, TruncatedJpegIsAnError) {
  const fs::path dir = WriteStrechaFolder("strecha_truncated");
  std::vector<unsigned char> jpeg;
  cv::Mat pixels(48, 64, CV_8UC3);
  cv::randu(pixels, 0, 255);
  ASSERT_TRUE(cv::imencode(".jpg", pixels, jpeg));
  // libjpeg decodes what is there and fills the rest: only its warning tells.
  std::ofstream(dir / "images" / "0001.jpg", std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(jpeg.size() / 2));
  ImportedSequence sequence;
  ASSERT_TRUE(ReadStrechaSequence(dir.string(), &sequence).ok());
  const Status status = WriteImportedSequence(sequence, SequenceWriteOptions(), (dir / "out").string());
  EXPECT_THAT(status.message(), HasSubstr("0001.jpg: cannot decode image (truncated: "));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// entry-P10 imported at the default 768x512: SIFT matches between consecutive images must lie on
// the epipolar lines of F from the imported K and poses. Measured medians 0.076, 0.114, 0.187 px
// (the provenance check found 0.16 px for pair 0-1 at full size).
TEST(StrechaImporterTest, EntryP10PosesAgreeWithScaledImages) {
  const std::string data = testing::SharedDataDir("strecha-entry-P10");
  if (data.empty()) GTEST_SKIP() << "../shared/data/strecha-entry-P10 is absent";
  const fs::path out = fs::path(testing::MakeScratchDir("strecha_entry")) / "sequence";
  ImportedSequence imported;
  ASSERT_TRUE(ReadStrechaSequence(data, &imported).ok());
  ASSERT_TRUE(WriteImportedSequence(imported, SequenceWriteOptions(), out.string()).ok());
  Sequence sequence;
  const Status read = ReadSequence(out.string(), &sequence);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(sequence.frames.size(), 10u);
  EXPECT_EQ(sequence.calibration.camera.width, 768);
  EXPECT_EQ(sequence.calibration.camera.height, 512);
  const Eigen::Matrix3d K = sequence.calibration.camera.K();

  const cv::Ptr<cv::SIFT> sift = cv::SIFT::create(2000);
  const cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<double> all;
  for (int pair : {0, 4, 8}) {
    cv::Mat images[2], descriptors[2];
    std::vector<cv::KeyPoint> keypoints[2];
    for (int k = 0; k < 2; ++k) {
      ASSERT_TRUE(LoadFrameImage(sequence, pair + k, &images[k]).ok());
      sift->detectAndCompute(images[k], cv::noArray(), keypoints[k], descriptors[k]);
    }
    std::vector<std::vector<cv::DMatch>> knn;
    matcher.knnMatch(descriptors[0], descriptors[1], knn, 2);
    const Eigen::Matrix3d F = FundamentalFromPoses(K, *sequence.frames[pair].world_T_base_groundtruth,
                                                   *sequence.frames[pair + 1].world_T_base_groundtruth);
    std::vector<double> distances;
    for (const std::vector<cv::DMatch>& m : knn) {
      if (m.size() < 2 || m[0].distance > 0.7 * m[1].distance) continue;  // Lowe's ratio test
      const cv::Point2f a = keypoints[0][m[0].queryIdx].pt, b = keypoints[1][m[0].trainIdx].pt;
      distances.push_back(SymmetricEpipolarDistance(F, {a.x, a.y}, {b.x, b.y}));
    }
    ASSERT_GT(distances.size(), 50u) << "pair " << pair;
    std::sort(distances.begin(), distances.end());
    std::cout << "[ figure   ] pair " << pair << "-" << pair + 1 << ": median epipolar distance "
              << distances[distances.size() / 2] << " px over " << distances.size() << " SIFT matches\n";
    EXPECT_LT(distances[distances.size() / 2], 0.5) << "pair " << pair;
    all.insert(all.end(), distances.begin(), distances.end());
  }
  std::sort(all.begin(), all.end());
  std::cout << "[ figure   ] all pairs: median epipolar distance " << all[all.size() / 2] << " px\n";
}

}  // namespace
}  // namespace sfm
