// detect_junctions: line segments and junctions of one image (docs/junctions.md,
// docs/junction_results.md).
//
//   build/bin/detect_junctions --image <file> [--camera sequence.yaml] [--json out.json]
//                              [--overlay out.png] [--segments fast|reference] [junction flags]
//
// With --camera the image is first undistorted with that calibration (junctions live in undistorted
// pixels); it must then be of the calibrated size. Writes the SPEC section 3 junction JSON (frame
// --frame, image = --image as given) and an overlay PNG: the image in grey, segments thin in cyan,
// junctions as dots coloured by type (legend top left) with their junction segments drawn from the
// location to their end-points. Errors are one line on stderr with a non-zero exit: 2 for bad
// flags, 1 for bad input or an output that cannot be written. Inputs and output directories are
// checked before anything is written; each file is written atomically.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/junctions_json.h"
#include "frontend/segments/segment_detector.h"
#include "frontend/junctions/undistorted_junctions.h"
#include "frontend/sequence/sequence.h"
#include "util/atomic_file.h"
#include "pipeline/overlay/junction_overlay.h"
#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::SegmentDetectorOptions kSegmentDefaults;
}  // namespace

DEFINE_string(image, "", "Image to read (required); any format OpenCV decodes, converted to 8-bit grey.");
DEFINE_string(camera, "", "Optional sequence.yaml: undistort the image with its calibration first.");
DEFINE_string(json, "", "Write the junctions here (SPEC section 3 JSON).");
DEFINE_string(overlay, "", "Write an overlay PNG here (segments, junctions coloured by type).");
DEFINE_int32(overlay_scale, 1, "Enlarge the overlay this many times (1..8), for sub-pixel detail.");
DEFINE_int32(frame, 0, "Frame index written into the JSON.");
DEFINE_double(min_segment_length, kSegmentDefaults.min_length, "Shortest segment kept, px.");
// --segments and the junction flags (--endpoint_lambda, --endpoint_mu, --junction_min_probability, ...) are
// shared with the other apps: sfm_app/flags/detector_flags.h.

namespace {

int Fail(int code, const std::string& message) {
  std::fprintf(stderr, "detect_junctions: %s\n", message.c_str());
  return code;
}

// The directory an output file goes to ("." for a bare name).
std::string ParentOf(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "line segments and junctions of one image.\n"
      "  detect_junctions --image <file> [--camera sequence.yaml] [--json out.json] [--overlay out.png] "
      "[--segments fast|reference] [junction flags]");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);

  // Flags.
  if (argc > 1) return Fail(2, std::string("unexpected argument '") + argv[1] + "' (flags are --name=value; see --help)");
  if (FLAGS_image.empty()) return Fail(2, "--image is required: the image to read");
  if (FLAGS_overlay_scale < 1 || FLAGS_overlay_scale > 8) return Fail(2, "--overlay_scale must be in 1..8");
  if (!FLAGS_overlay.empty() && std::filesystem::path(FLAGS_overlay).extension() != ".png") {
    return Fail(2, "--overlay must name a .png file, not '" + FLAGS_overlay + "'");
  }
  sfm::SegmentDetectorOptions segment_options;
  std::string flag_error;
  if (!sfm::SegmentMethodFromFlags(&segment_options, &flag_error)) return Fail(2, flag_error);
  sfm::UndistortInterpolation interpolation;
  if (!sfm::UndistortInterpolationFromFlags(&interpolation, &flag_error)) return Fail(2, flag_error);
  segment_options.min_length = FLAGS_min_segment_length;
  sfm::JunctionDetectorOptions junction_options;
  sfm::JunctionDetectorFromFlags(&junction_options);
  for (const sfm::Status& check : {segment_options.Check(), junction_options.Check()}) {
    if (!check.ok()) return Fail(2, check.message());
  }

  // Input.
  std::error_code error;
  if (!std::filesystem::is_regular_file(FLAGS_image, error)) return Fail(1, FLAGS_image + ": no such file");
  cv::Mat grey = cv::imread(FLAGS_image, cv::IMREAD_GRAYSCALE);
  if (grey.empty()) return Fail(1, FLAGS_image + ": cannot decode as an image");
  // With --camera and --undistort_full_view, detection runs on the full-view canvas (an
  // equidistant lens: its perspective sub-views) and the junctions come back in K's pixels
  // (possibly outside the image; the overlay clips them).
  std::unique_ptr<sfm::ImageUndistorter> undistorter;
  cv::Mat stored;
  if (!FLAGS_camera.empty()) {
    sfm::Calibration calibration;
    const sfm::Status read = sfm::ReadCalibration(FLAGS_camera, &calibration);
    if (!read.ok()) return Fail(1, read.message());
    const sfm::Camera& camera = calibration.camera;
    if (grey.cols != camera.width || grey.rows != camera.height) {
      return Fail(1, FLAGS_image + ": image is " + std::to_string(grey.cols) + "x" + std::to_string(grey.rows) +
                         " but " + FLAGS_camera + " calibrates " + std::to_string(camera.width) + "x" +
                         std::to_string(camera.height));
    }
    undistorter =
        std::make_unique<sfm::ImageUndistorter>(camera, interpolation, sfm::UndistortViewFromFlags());
    stored = grey;
    grey = sfm::ImageUndistorter(camera, interpolation).Apply(grey);  // the overlay's background
  }
  for (const std::string* output : {&FLAGS_json, &FLAGS_overlay}) {
    if (output->empty()) continue;
    if (std::filesystem::is_directory(*output, error)) return Fail(1, *output + ": is a directory, not a file");
    const sfm::Status writable = sfm::EnsureWritableDirectory(ParentOf(*output));
    if (!writable.ok()) return Fail(1, writable.message());
  }

  // Detection.
  sfm::LineSegments segments;
  sfm::Junctions junctions;
  if (undistorter) {
    junctions =
        sfm::DetectUndistortedJunctions(*undistorter, stored, segment_options, junction_options, &segments);
  } else {
    segments = sfm::DetectLineSegments(grey, segment_options);
    junctions = sfm::DetectJunctions(segments, junction_options);
  }

  // Output.
  if (!FLAGS_json.empty()) {
    const std::string json = sfm::JunctionsToJson(FLAGS_frame, FLAGS_image, grey.cols, grey.rows, junctions);
    const sfm::Status written = sfm::WriteFileAtomically(FLAGS_json, json);
    if (!written.ok()) return Fail(1, written.message());
  }
  if (!FLAGS_overlay.empty()) {
    const cv::Mat overlay = sfm::DrawJunctionOverlay(grey, segments, junctions, FLAGS_overlay_scale);
    std::vector<uchar> png;
    if (!cv::imencode(".png", overlay, png)) return Fail(1, FLAGS_overlay + ": PNG encoding failed");
    const sfm::Status written = sfm::WriteFileAtomically(FLAGS_overlay, std::string(png.begin(), png.end()));
    if (!written.ok()) return Fail(1, written.message());
  }
  int counts[6] = {0, 0, 0, 0, 0, 0};
  for (const sfm::Junction& j : junctions) ++counts[static_cast<int>(j.type)];
  std::printf("detect_junctions: %s: %zu segments, %zu junctions (L %d, Y %d, ARROW %d, T %d, X %d, N %d)\n",
              FLAGS_image.c_str(), segments.size(), junctions.size(), counts[0], counts[1], counts[2], counts[3],
              counts[4], counts[5]);
  return 0;
}
