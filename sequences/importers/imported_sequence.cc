#include "sequences/importers/imported_sequence.h"

#include <glog/logging.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <utility>

#include "geometry/tum_io.h"
#include "frontend/sequence/sequence.h"
#include "util/atomic_file.h"
#include "util/number_text.h"
#include "sequences/importers/input_files.h"
#include "sequences/importers/sequence_output.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

std::string SizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// The data set's image size of the frames (that of the camera unless the frames are warped).
cv::Size SourceSize(const ImportedSequence& sequence) {
  return sequence.source_width > 0 ? cv::Size(sequence.source_width, sequence.source_height)
                                   : cv::Size(sequence.camera.width, sequence.camera.height);
}

// Decodes, checks, warps (when the frame says so) and scales one image, and writes it as PNG.
Status WriteFrameImage(const ImportedFrame& frame, const ImportedSequence& sequence, const cv::Size& size,
                       const fs::path& target) {
  const std::string& source = frame.source_image;
  cv::Mat image;
  // 8-bit grey or colour, whatever the file holds (the pipeline converts to grey itself).
  SFM_RETURN_IF_ERROR(DecodeImage(source, cv::IMREAD_ANYCOLOR, &image));
  const cv::Size source_size = SourceSize(sequence);
  if (image.size() != source_size) {
    return Status::Error(source + ": image is " + SizeText(image.cols, image.rows) + ", expected " +
                         SizeText(source_size.width, source_size.height));
  }
  if (frame.source_to_image) {
    // Bicubic: less smoothing than bilinear at the fractional shifts of a warp, so the junctions'
    // gradients stay as sharp in every frame. warpAffine maps destination pixel centres through the
    // inverse of A, the same convention as A. The replicated border is never read inside the crop
    // (shared_intrinsics_warp.h keeps a margin for the bicubic support).
    cv::Mat A;
    cv::eigen2cv(Eigen::Matrix<double, 2, 3>(*frame.source_to_image), A);
    cv::Mat warped;
    cv::warpAffine(image, warped, A, cv::Size(sequence.camera.width, sequence.camera.height), cv::INTER_CUBIC,
                   cv::BORDER_REPLICATE);
    image = warped;
  }
  // INTER_AREA averages whole source pixels: no aliasing when shrinking, and it keeps the
  // pixel-centre mapping that ScaleCamera assumes.
  if (image.size() != size) cv::resize(cv::Mat(image), image, size, 0, 0, cv::INTER_AREA);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) return Status::Error(target.string() + ": PNG encoding failed");
  return WriteFileAtomically(target.string(), std::string(png.begin(), png.end()));
}

std::string NotesText(const ImportedSequence& sequence, const SequenceWriteOptions& options, const Camera& camera) {
  const CameraOdometryNoiseOptions& noise = options.odometry;
  std::string text = "# How this sequence was imported (import_sequence; see docs/importers.md)\n";
  for (const std::string& note : sequence.notes) text += note + "\n";
  const std::string source_size = SizeText(sequence.camera.width, sequence.camera.height);
  text += camera.width == sequence.camera.width && camera.height == sequence.camera.height
              ? "images: " + source_size + ", not scaled\n"
              : "images: " + source_size + " scaled to " + SizeText(camera.width, camera.height) +
                    " (K scaled with the pixel-centre convention, cx' = s (cx + 0.5) - 0.5)\n";
  text += "odometry: simulated from groundtruth.txt, seed " + std::to_string(options.seed) + ", scale_error " +
          ShortestNumberText(noise.scale_error) + ", distance_sigma " + ShortestNumberText(noise.distance_sigma) +
          ", rotation_sigma " + ShortestNumberText(noise.rotation_sigma) + " rad, rotation_bias " +
          ShortestNumberText(noise.rotation_bias) + " rad (camera y axis)\n";
  return text;
}

// image_warps.txt: per frame, the affine map from the data set's pixels to the written image's,
// the frame's warp followed by the scaling (x' = s (x + 0.5) - 0.5, image_scaling.h). Empty when no
// frame is warped.
std::string WarpsText(const ImportedSequence& sequence, const Camera& scaled) {
  bool any = false;
  for (const ImportedFrame& frame : sequence.frames) any = any || frame.source_to_image.has_value();
  if (!any) return "";
  const double sx = static_cast<double>(scaled.width) / sequence.camera.width;
  const double sy = static_cast<double>(scaled.height) / sequence.camera.height;
  Eigen::Matrix3d scaling;
  scaling << sx, 0, 0.5 * sx - 0.5, 0, sy, 0.5 * sy - 0.5, 0, 0, 1;
  std::string text =
      "# image a11 a12 a13 a21 a22 a23: pixel of the image = [a11 a12 a13; a21 a22 a23] (pixel of the data "
      "set's "
      "image; 1), OpenCV pixel-centre convention (import_sequence; docs/importers.md)\n";
  for (size_t i = 0; i < sequence.frames.size(); ++i) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
    if (sequence.frames[i].source_to_image) A.topRows<2>() = *sequence.frames[i].source_to_image;
    const Eigen::Matrix3d total = scaling * A;
    char name[32];
    std::snprintf(name, sizeof(name), "images/%06zu.png", i);
    text += name;
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 3; ++c) text += " " + ShortestNumberText(total(r, c));
    }
    text += "\n";
  }
  return text;
}

}  // namespace

Status SequenceWriteOptions::Check() const {
  SFM_RETURN_IF_ERROR(scale.Check());
  return odometry.Check();
}

Status WriteImportedSequence(const ImportedSequence& sequence, const SequenceWriteOptions& options,
                             const std::string& output_dir) {
  SFM_RETURN_IF_ERROR(options.Check());
  if (sequence.frames.size() < 2) {
    return Status::Error("import: " + std::to_string(sequence.frames.size()) + " frame(s), a sequence needs at least 2");
  }
  const fs::path target = NormalisedTarget(output_dir);
  fs::path temporary_path;
  SFM_RETURN_IF_ERROR(PrepareOutputDirectory(target, options.overwrite, &temporary_path));
  TemporaryDirectory temporary(temporary_path);
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((temporary.path() / "images").string()));

  const cv::Size size = ScaledImageSize(sequence.camera.width, sequence.camera.height, options.scale);
  Calibration calibration;
  calibration.camera = ScaleCamera(sequence.camera, size);
  calibration.base_T_camera = Pose3::Identity();  // SPEC: a data set that gives camera poses
  calibration.odometry_noise = options.odometry.ForCalibration();
  calibration.odometry_noise_given = true;

  std::vector<Pose3> truth;
  for (const ImportedFrame& frame : sequence.frames) truth.push_back(frame.world_T_camera);
  const std::vector<Pose3> odometry = SimulateCameraOdometry(truth, options.odometry, options.seed);

  std::string image_list = "# timestamp image (imported by import_sequence; see import_notes.txt)\n";
  std::vector<StampedPose> groundtruth_poses, odometry_poses;
  for (size_t i = 0; i < sequence.frames.size(); ++i) {
    const ImportedFrame& frame = sequence.frames[i];
    char name[32];
    std::snprintf(name, sizeof(name), "images/%06zu.png", i);
    SFM_RETURN_IF_ERROR(WriteFrameImage(frame, sequence, size, temporary.path() / name));
    image_list += ShortestNumberText(frame.timestamp) + " " + name + "\n";
    groundtruth_poses.push_back({frame.timestamp, truth[i]});
    odometry_poses.push_back({frame.timestamp, odometry[i]});
  }
  const fs::path& root = temporary.path();
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "images.txt").string(), image_list));
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "groundtruth.txt").string(), groundtruth_poses));
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "odometry.txt").string(), odometry_poses));
  SFM_RETURN_IF_ERROR(WriteCalibration((root / "sequence.yaml").string(), calibration));
  const std::string warps = WarpsText(sequence, calibration.camera);
  if (!warps.empty()) SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "image_warps.txt").string(), warps));
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "import_notes.txt").string(),
                                          NotesText(sequence, options, calibration.camera)));
  SFM_RETURN_IF_ERROR(MoveIntoPlace(&temporary, target));
  LOG(INFO) << "import: wrote " << sequence.frames.size() << " frames of " << SizeText(size.width, size.height)
            << " to " << target.string();
  return Status::Ok();
}

Status ReadImageWarps(const std::string& path, std::vector<Eigen::Matrix<double, 2, 3>>* warps) {
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot be read");
  warps->clear();
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string image;
    Eigen::Matrix<double, 2, 3> A;
    fields >> image >> A(0, 0) >> A(0, 1) >> A(0, 2) >> A(1, 0) >> A(1, 1) >> A(1, 2);
    std::string extra;
    if (!fields || (fields >> extra) || !A.allFinite()) {
      return Status::Error(path + ": line " + std::to_string(number) +
                           " is not 'image a11 a12 a13 a21 a22 a23' with six finite numbers");
    }
    warps->push_back(A);
  }
  return Status::Ok();
}

}  // namespace sfm
