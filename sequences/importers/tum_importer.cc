#include "sequences/importers/tum_importer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glog/logging.h>

#include "geometry/tum_io.h"
#include "util/text_file.h"
#include "sequences/importers/input_files.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

struct TumImage {
  double timestamp = 0;
  std::string path;  // absolute or relative to the working directory
  int line = 0;      // in rgb.txt
};

Status ReadImageList(const fs::path& dir, const std::string& path, std::vector<TumImage>* images) {
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(path, &lines));
  for (const DataLine& line : lines) {
    const std::string& where = line.where;
    const std::vector<std::string> words = SplitWords(line.text);
    TumImage image;
    if (words.size() != 2 || !ParseDouble(words[0], &image.timestamp) || !std::isfinite(image.timestamp)) {
      return Status::Error(where + "expected '<timestamp> <image file>', found '" + line.text + "'");
    }
    if (!images->empty() && !(image.timestamp > images->back().timestamp)) {
      return Status::Error(where + "timestamp " + words[0] + " is not after the previous line's");
    }
    image.path = (dir / words[1]).string();
    image.line = line.number;
    images->push_back(image);
  }
  if (images->empty()) return Status::Error(path + ": lists no image");
  return Status::Ok();
}

}  // namespace

Status ParseTumCamera(const std::string& name, TumCamera* camera) {
  if (name == "fr1") {
    *camera = TumCamera::kFreiburg1;
  } else if (name == "fr2") {
    *camera = TumCamera::kFreiburg2;
  } else if (name == "fr3") {
    *camera = TumCamera::kFreiburg3;
  } else {
    return Status::Error("unknown TUM camera '" + name + "' (expected fr1, fr2 or fr3)");
  }
  return Status::Ok();
}

Camera TumCameraModel(TumCamera which) {
  // vision.in.tum.de/data/datasets/rgbd-dataset/file_formats, "Intrinsic Camera Calibration".
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  switch (which) {
    case TumCamera::kFreiburg1:
      camera.fx = 517.306408, camera.fy = 516.469215, camera.cx = 318.643040, camera.cy = 255.313989;
      camera.distortion = {0.262383, -0.953104, -0.005358, 0.002628, 1.163314};
      break;
    case TumCamera::kFreiburg2:
      camera.fx = 520.908620, camera.fy = 521.007327, camera.cx = 325.141442, camera.cy = 249.701764;
      camera.distortion = {0.231222, -0.784899, -0.003257, -0.000105, 0.917205};
      break;
    case TumCamera::kFreiburg3:
      camera.fx = 535.4, camera.fy = 539.2, camera.cx = 320.1, camera.cy = 247.6;
      break;
  }
  return camera;
}

Status TumImportOptions::Check() const {
  if (stride < 1) return Status::Error("TUM stride must be >= 1");
  if (!(max_groundtruth_gap > 0)) return Status::Error("max_groundtruth_gap must be > 0 s");
  return Status::Ok();
}

Status ReadTumSequence(const std::string& input_dir, const TumImportOptions& options, ImportedSequence* sequence) {
  SFM_RETURN_IF_ERROR(options.Check());
  const fs::path dir(input_dir);
  std::error_code error;
  if (!fs::is_directory(dir, error)) return Status::Error(input_dir + ": input directory does not exist");
  const std::string list_path = (dir / "rgb.txt").string(), truth_path = (dir / "groundtruth.txt").string();
  if (!fs::is_regular_file(list_path, error)) return Status::Error(list_path + ": file does not exist");
  if (!fs::is_regular_file(truth_path, error)) return Status::Error(truth_path + ": file does not exist");
  std::vector<TumImage> images;
  SFM_RETURN_IF_ERROR(ReadImageList(dir, list_path, &images));
  std::vector<StampedPose> truth;
  SFM_RETURN_IF_ERROR(ReadTumTrajectory(truth_path, &truth));

  ImportedSequence imported;
  imported.camera = TumCameraModel(options.camera);
  int with_truth = 0, outside = 0, in_gap = 0;
  for (const TumImage& image : images) {
    const auto after = std::lower_bound(truth.begin(), truth.end(), image.timestamp,
                                        [](const StampedPose& pose, double t) { return pose.timestamp < t; });
    if (after == truth.end() || (after == truth.begin() && after->timestamp != image.timestamp)) {
      ++outside;
      continue;
    }
    Pose3 world_T_camera = after->pose;
    if (after->timestamp != image.timestamp) {
      const StampedPose& before = *(after - 1);
      const double gap = after->timestamp - before.timestamp;
      if (gap > options.max_groundtruth_gap) {
        ++in_gap;
        continue;
      }
      world_T_camera = InterpolatePose(before.pose, after->pose, (image.timestamp - before.timestamp) / gap);
    }
    if (with_truth++ % options.stride != 0) continue;
    if (!fs::is_regular_file(image.path, error)) {
      return Status::Error(list_path + ":" + std::to_string(image.line) + ": image file " + image.path +
                           " does not exist");
    }
    imported.frames.push_back({image.timestamp, image.path, world_T_camera, std::nullopt});
  }
  LOG(INFO) << "TUM: " << images.size() << " images in rgb.txt, " << outside << " outside the ground truth's time span, "
            << in_gap << " in ground-truth gaps over " << options.max_groundtruth_gap << " s; kept "
            << imported.frames.size() << " (stride " << options.stride << ")";
  if (imported.frames.size() < 2) {
    return Status::Error(list_path + ": only " + std::to_string(imported.frames.size()) +
                         " image(s) have ground truth (" + std::to_string(outside) + " outside its time span, " +
                         std::to_string(in_gap) + " in gaps); a sequence needs at least 2");
  }
  const char* const names[] = {"fr1", "fr2", "fr3"};
  imported.notes.push_back("format: TUM RGB-D, " + input_dir + ", " + std::to_string(imported.frames.size()) +
                           " of " + std::to_string(images.size()) + " images (stride " +
                           std::to_string(options.stride) + ")");
  imported.notes.push_back(std::string("K and distortion: the published ") +
                           names[static_cast<int>(options.camera)] + " colour camera calibration");
  imported.notes.push_back("poses: groundtruth.txt interpolated (slerp) at each image's timestamp, metres");
  *sequence = std::move(imported);
  return Status::Ok();
}

}  // namespace sfm
