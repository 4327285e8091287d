#include "sequences/importers/vgg_importer.h"

#include <glog/logging.h>

#include <Eigen/LU>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "util/number_text.h"
#include "sequences/importers/input_files.h"
#include "sequences/importers/projection_decomposition.h"
#include "sequences/importers/shared_intrinsics_warp.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

using Matrix34d = Eigen::Matrix<double, 3, 4>;

// PnP needs a few points; fewer in view means the camera does not look at the reconstructed scene.
constexpr int kMinPointsInView = 6;

struct View {
  std::string stem;  // <name>.NNN
  std::string camera_path, image_path;
  Matrix34d P;       // in the sequence's world frame
  ProjectionDecomposition decomposition;
};

// The <name>.NNN.P files of the folder in NNN order; fails unless there are some, all of one name.
Status ListViews(const fs::path& dir, std::vector<View>* views, std::string* name) {
  std::map<long, View> by_number;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, error)) {
    const std::string file = entry.path().filename().string();
    if (file.size() < 2 || file.substr(file.size() - 2) != ".P") continue;
    const std::string stem = file.substr(0, file.size() - 2);
    const size_t dot = stem.rfind('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == stem.size()) continue;
    const std::string number = stem.substr(dot + 1);
    if (!std::all_of(number.begin(), number.end(), [](unsigned char c) { return std::isdigit(c); })) continue;
    const std::string this_name = stem.substr(0, dot);
    if (!name->empty() && this_name != *name) {
      return Status::Error(dir.string() + ": camera files of two sequences (" + *name + ".NNN.P and " + this_name +
                           ".NNN.P); keep one per folder");
    }
    *name = this_name;
    View view;
    view.stem = stem;
    view.camera_path = entry.path().string();
    view.image_path = (dir / (stem + ".pgm")).string();
    by_number[std::stol(number)] = view;
  }
  if (error) return Status::Error(dir.string() + ": cannot list (" + error.message() + ")");
  if (by_number.empty()) return Status::Error(dir.string() + ": no VGG camera files (<name>.NNN.P)");
  for (auto& [number, view] : by_number) views->push_back(std::move(view));
  return Status::Ok();
}

Status ReadProjection(const std::string& path, Matrix34d* P) {
  std::vector<double> numbers;
  SFM_RETURN_IF_ERROR(ReadNumbers(path, &numbers));
  if (numbers.size() != 12) {
    return Status::Error(path + ": expected 12 numbers (a 3x4 camera matrix), found " + std::to_string(numbers.size()));
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) (*P)(r, c) = numbers[4 * r + c];
  }
  return Status::Ok();
}

Status ReadPoints(const std::string& path, std::vector<Eigen::Vector3d>* points) {
  std::vector<double> numbers;
  SFM_RETURN_IF_ERROR(ReadNumbers(path, &numbers));
  if (numbers.empty() || numbers.size() % 3 != 0) {
    return Status::Error(path + ": expected 'X Y Z' per line, found " + std::to_string(numbers.size()) +
                         " numbers in all");
  }
  for (size_t i = 0; i < numbers.size(); i += 3) points->emplace_back(numbers[i], numbers[i + 1], numbers[i + 2]);
  return Status::Ok();
}

bool InsideImage(const Eigen::Vector2d& pixel, const cv::Size& size) {
  return pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() <= size.width - 0.5 && pixel.y() <= size.height - 0.5;
}

// True when most points that project into the images lie behind the cameras as a right-handed
// world frame sees them (H&Z eq. 6.15: depth has the sign of det(M) w): the files' frame is then
// left-handed. P and -P project alike, so the points are needed to tell.
bool WorldIsMirrored(const std::vector<View>& views, const std::vector<Eigen::Vector3d>& points, const cv::Size& size) {
  long in_front = 0, behind = 0;
  for (const View& view : views) {
    const double determinant_sign = view.P.leftCols<3>().determinant() > 0 ? 1 : -1;
    for (const Eigen::Vector3d& X : points) {
      const Eigen::Vector3d x = view.P * X.homogeneous();
      if (x.z() == 0 || !InsideImage(x.hnormalized(), size)) continue;
      (determinant_sign * x.z() > 0 ? in_front : behind) += 1;
    }
  }
  return behind > in_front;
}

// The pose for the shared K that best reproduces P's projections of the 3D points in view
// (Levenberg-Marquardt on the reprojection error, from the decomposed pose).
Status RefitPose(const View& view, const std::vector<Eigen::Vector3d>& points, const cv::Size& size,
                 const Eigen::Matrix3d& K, Pose3* camera_T_world, double* rms_px) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const Eigen::Vector3d& X : points) {
    if ((view.decomposition.camera_T_world * X).z() <= 0) continue;
    const Eigen::Vector2d x = (view.P * X.homogeneous()).hnormalized();
    if (!InsideImage(x, size)) continue;
    object.emplace_back(X.x(), X.y(), X.z());
    image.emplace_back(x.x(), x.y());
  }
  if (static_cast<int>(object.size()) < kMinPointsInView) {
    return Status::Error(view.camera_path + ": only " + std::to_string(object.size()) +
                         " of the 3D points lie in front of this camera and inside its image; at least " +
                         std::to_string(kMinPointsInView) + " are needed");
  }
  cv::Mat K_cv, rotation, rotation_vector, translation;
  cv::eigen2cv(K, K_cv);
  cv::eigen2cv(Eigen::Matrix3d(view.decomposition.camera_T_world.RotationMatrix()), rotation);
  cv::Rodrigues(rotation, rotation_vector);
  cv::eigen2cv(Eigen::Vector3d(view.decomposition.camera_T_world.translation), translation);
  cv::solvePnP(object, image, K_cv, cv::noArray(), rotation_vector, translation, /*useExtrinsicGuess=*/true,
               cv::SOLVEPNP_ITERATIVE);
  cv::Rodrigues(rotation_vector, rotation);
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  cv::cv2eigen(rotation, R);
  cv::cv2eigen(translation, t);
  *camera_T_world = Pose3(R, t);
  double sum = 0;
  for (size_t i = 0; i < object.size(); ++i) {
    const Eigen::Vector2d x = (K * (R * Eigen::Vector3d(object[i].x, object[i].y, object[i].z) + t)).hnormalized();
    sum += (x - Eigen::Vector2d(image[i].x, image[i].y)).squaredNorm();
  }
  *rms_px = std::sqrt(sum / object.size());
  return Status::Ok();
}

// <name>.NNN.corners: 'x y' per line.
Status ReadCorners(const std::string& path, std::vector<Eigen::Vector2d>* corners) {
  std::vector<double> numbers;
  SFM_RETURN_IF_ERROR(ReadNumbers(path, &numbers));
  if (numbers.size() % 2 != 0) {
    return Status::Error(path + ": expected 'x y' per line, found " + std::to_string(numbers.size()) +
                         " numbers in all");
  }
  for (size_t i = 0; i < numbers.size(); i += 2) corners->emplace_back(numbers[i], numbers[i + 1]);
  return Status::Ok();
}

// <name>.nview-corners (README-2D): one row per 3D point, per view the index of its corner in that
// view's .corners or '*'; as observations of point (row) in view (column).
Status ReadCornerTracks(const std::string& path, size_t point_count,
                        const std::vector<std::vector<Eigen::Vector2d>>& corners,
                        std::vector<RefitObservation>* observations) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return Status::Error(path + ": file does not exist");
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  std::string line;
  size_t row = 0;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (tokens.size() != corners.size()) {
      return Status::Error(where + ": expected one entry per view (" + std::to_string(corners.size()) +
                           "), found " + std::to_string(tokens.size()));
    }
    if (row >= point_count) {
      return Status::Error(where + ": more rows than 3D points (" + std::to_string(point_count) + ")");
    }
    for (size_t v = 0; v < tokens.size(); ++v) {
      if (tokens[v] == "*") continue;
      const std::string& token = tokens[v];
      if (!std::all_of(token.begin(), token.end(), [](unsigned char c) { return std::isdigit(c); }) ||
          token.size() > 9) {
        return Status::Error(where + ": '" + token + "' is neither a corner index nor '*'");
      }
      const size_t index = std::stoul(token);
      if (index >= corners[v].size()) {
        return Status::Error(where + ": corner " + token + " of view " + std::to_string(v) +
                             " does not exist (" + std::to_string(corners[v].size()) + " corners)");
      }
      observations->push_back({static_cast<int>(v), static_cast<int>(row), corners[v][index]});
    }
    ++row;
  }
  if (row != point_count) {
    return Status::Error(path + ": " + std::to_string(row) + " rows for " + std::to_string(point_count) +
                         " 3D points");
  }
  return Status::Ok();
}

// <name>.NNN.lines (README-2D): 'x0 y0 x1 y1' and possibly more fields per line; the end points.
Status ReadSegments(const std::string& path, int image, std::vector<PlumbLineSegment>* segments) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return Status::Error(path + ": file does not exist");
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    std::istringstream fields(line);
    double x0, y0, x1, y1;
    if (!(fields >> x0)) continue;  // a blank line
    if (!(fields >> y0 >> x1 >> y1) || !std::isfinite(x0 + y0 + x1 + y1)) {
      return Status::Error(path + ":" + std::to_string(line_number) + ": expected 'x0 y0 x1 y1'");
    }
    segments->push_back({image, Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1)});
  }
  return Status::Ok();
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string FixedText(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

// "a..b" of the values, for the log and the notes.
std::string RangeText(const std::vector<double>& values, int decimals = 1) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f..%.*f", decimals, *low, decimals, *high);
  return text;
}

}  // namespace

Eigen::Vector3d VggFileToWorld(const Eigen::Vector3d& point_in_file, bool world_mirrored) {
  return world_mirrored ? Eigen::Vector3d(-point_in_file) : point_in_file;
}

Status ReadVggSequence(const std::string& input_dir, const VggImportOptions& options, ImportedSequence* sequence,
                       VggImportSummary* summary) {
  const fs::path dir(input_dir);
  std::error_code error;
  if (!fs::is_directory(dir, error)) return Status::Error(input_dir + ": input directory does not exist");
  std::vector<View> views;
  std::string name;
  SFM_RETURN_IF_ERROR(ListViews(dir, &views, &name));
  for (View& view : views) {
    if (!fs::is_regular_file(view.image_path, error)) {
      return Status::Error(view.image_path + ": image file for " + view.stem + ".P does not exist");
    }
    SFM_RETURN_IF_ERROR(ReadProjection(view.camera_path, &view.P));
  }
  const std::string points_path = (dir / (name + ".p3d")).string();
  std::vector<Eigen::Vector3d> points;
  SFM_RETURN_IF_ERROR(ReadPoints(points_path, &points));

  cv::Mat first_image;
  SFM_RETURN_IF_ERROR(DecodeImage(views.front().image_path, cv::IMREAD_GRAYSCALE, &first_image));
  const cv::Size size = first_image.size();

  VggImportSummary result;
  result.world_mirrored = WorldIsMirrored(views, points, size);
  if (result.world_mirrored) {
    // P_world = P_file diag(-1, -1, -1, 1), so that P_world X_world = P_file X_file.
    for (View& view : views) view.P.leftCols<3>() *= -1;
    for (Eigen::Vector3d& X : points) X = VggFileToWorld(X, true);
  }
  std::vector<double> fx, fy, cx, cy, skew;
  for (View& view : views) {
    const Status status = DecomposeProjection(view.P, &view.decomposition);
    if (!status.ok()) return Status::Error(view.camera_path + ": " + status.message());
    const Eigen::Matrix3d& K = view.decomposition.K;
    fx.push_back(K(0, 0));
    fy.push_back(K(1, 1));
    cx.push_back(K(0, 2));
    cy.push_back(K(1, 2));
    skew.push_back(std::abs(K(0, 1)));
  }
  result.K << Median(fx), 0, Median(cx), 0, Median(fy), Median(cy), 0, 0, 1;
  std::string k_note = "K: median of the " + std::to_string(views.size()) + " frames' decomposed K (fx " +
                       RangeText(fx) + ", fy " + RangeText(fy) + ", cx " + RangeText(cx) + ", cy " +
                       RangeText(cy) + ", |skew| " + RangeText(skew) + " set to 0): fx " +
                       ShortestNumberText(result.K(0, 0)) + " fy " + ShortestNumberText(result.K(1, 1)) +
                       " cx " + ShortestNumberText(result.K(0, 2)) + " cy " +
                       ShortestNumberText(result.K(1, 2));
  LOG(INFO) << "VGG: one " << k_note;

  ImportedSequence imported;
  imported.camera.width = size.width;
  imported.camera.height = size.height;
  std::string pose_note;
  if (options.warp_to_shared_k) {
    std::vector<Eigen::Matrix3d> frame_K;
    for (const View& view : views) frame_K.push_back(view.decomposition.K);
    SharedIntrinsicsWarp warp;
    const Status status = WarpToSharedIntrinsics(frame_K, size.width, size.height, result.K, &warp);
    if (!status.ok()) return Status::Error(input_dir + ": " + status.message());
    imported.source_width = size.width;
    imported.source_height = size.height;
    imported.camera.width = warp.width;
    imported.camera.height = warp.height;
    result.K = warp.K;
    result.source_to_image = warp.source_to_image;
    pose_note =
        "poses: R, C of each P's RQ decomposition, exact for the warped images; images resampled (bicubic) "
        "by H_i = K K_i^-1 to that K and cropped to the " +
        std::to_string(warp.width) + "x" + std::to_string(warp.height) +
        " rectangle every warped frame covers (cx, cy moved by the crop to " +
        ShortestNumberText(warp.K(0, 2)) + ", " + ShortestNumberText(warp.K(1, 2)) +
        "); image_warps.txt maps the data set's pixels to the sequence's";
    LOG(INFO) << "VGG: " << pose_note;
  } else {
    pose_note = options.refit_poses
                    ? "poses: re-estimated for the median K (PnP on " + name + ".p3d as each P projects it)"
                    : "poses: R, C of each P's RQ decomposition (with its own K, not the shared one)";
  }
  std::vector<Pose3> camera_T_world;
  for (const View& view : views) camera_T_world.push_back(view.decomposition.camera_T_world);
  const bool refit = options.refit_poses && !options.warp_to_shared_k;
  for (size_t i = 0; i < views.size(); ++i) {
    double rms_px = 0;
    if (refit) {
      SFM_RETURN_IF_ERROR(RefitPose(views[i], points, size, result.K, &camera_T_world[i], &rms_px));
      LOG(INFO) << "VGG: " << views[i].stem << ": pose refitted for the median K, RMS " << rms_px
                << " px against P";
    }
    result.refit_rms_px.push_back(rms_px);
  }
  if (refit) pose_note += "; RMS " + RangeText(result.refit_rms_px) + " px";
  std::string refit_note;
  // The joint refit needs the data set's corner tracks; a data set without them keeps the PnP truth
  // (with a warning and a note) rather than failing to import.
  std::string missing_corners;
  for (const View& view : views) {
    if (!fs::is_regular_file(dir / (view.stem + ".corners"))) missing_corners = view.stem + ".corners";
  }
  if (!fs::is_regular_file(dir / (name + ".nview-corners"))) missing_corners = name + ".nview-corners";
  if (refit && options.refit == VggRefit::kJoint && !missing_corners.empty()) {
    LOG(WARNING) << "VGG: " << (dir / missing_corners).string()
                 << " does not exist: no joint refit, the poses stay the PnP fit for the median K";
    pose_note += "; no joint refit (" + missing_corners + " missing)";
  }
  if (refit && options.refit == VggRefit::kJoint && missing_corners.empty()) {
    // Started from the median K and the PnP poses above; the P files' own centres fix the gauge.
    std::vector<std::vector<Eigen::Vector2d>> corners(views.size());
    for (size_t i = 0; i < views.size(); ++i) {
      SFM_RETURN_IF_ERROR(ReadCorners((dir / (views[i].stem + ".corners")).string(), &corners[i]));
    }
    std::vector<RefitObservation> observations;
    const std::string tracks_path = (dir / (name + ".nview-corners")).string();
    SFM_RETURN_IF_ERROR(ReadCornerTracks(tracks_path, points.size(), corners, &observations));
    std::vector<Eigen::Vector3d> reference_centres;
    for (const View& view : views) reference_centres.push_back(view.decomposition.centre);
    double k1 = options.k1;
    std::string no_plumb_line;  // why k1 stayed 0 although asked for from the lines
    if (options.k1_from_lines) {
      if (options.k1 != 0) return Status::Error(input_dir + ": a k1 given and k1 from the lines: choose one");
      std::vector<cv::Mat> images;
      std::vector<PlumbLineSegment> segments;
      for (size_t i = 0; i < views.size() && no_plumb_line.empty(); ++i) {
        const fs::path lines_path = dir / (views[i].stem + ".lines");
        if (!fs::is_regular_file(lines_path)) {
          no_plumb_line = lines_path.string() + " does not exist";
          break;
        }
        cv::Mat image;
        SFM_RETURN_IF_ERROR(DecodeImage(views[i].image_path, cv::IMREAD_GRAYSCALE, &image));
        images.push_back(image);
        SFM_RETURN_IF_ERROR(ReadSegments(lines_path.string(), static_cast<int>(i), &segments));
      }
      PlumbLineEstimate plumb_line;
      if (no_plumb_line.empty()) {
        const Status status =
            EstimateRadialDistortionFromEdges(images, segments, result.K, PlumbLineOptions(), &plumb_line);
        if (!status.ok()) no_plumb_line = status.message();
      }
      if (no_plumb_line.empty()) {
        k1 = plumb_line.k1;
        result.plumb_line = plumb_line;
        LOG(INFO) << "VGG: k1 " << plumb_line.k1 << " +- " << plumb_line.k1_sigma << " from the bows of "
                  << plumb_line.edges << " long straight edges (plumb line)";
      } else {
        // A data set without long straight segments (or without .lines files) is imported as the P
        // files model it, without distortion, rather than refused.
        LOG(WARNING) << "VGG: no plumb-line k1 (" << no_plumb_line << "): k1 = 0";
      }
    }
    SharedCameraRefitOptions refit_options;
    refit_options.refine_focal = options.refit_focal;
    refit_options.refine_principal_point = options.refit_principal_point;
    refit_options.radial_k1 = options.refit_radial_k1;
    refit_options.k1 = k1;
    SharedCameraRefit joint;
    const Status status = RefitSharedCamera(result.K, camera_T_world, points, observations, reference_centres,
                                            refit_options, &joint);
    if (!status.ok()) return Status::Error(tracks_path + ": " + status.message());
    result.K = joint.K;
    camera_T_world = joint.camera_T_world;
    imported.camera.distortion[0] = joint.k1;
    std::string held = options.refit_focal ? "" : " fx fy";
    if (!options.refit_principal_point) held += " cx cy";
    refit_note =
        "joint refit (bundle adjustment, sequences/importers/shared_camera_refit.h) of the " +
        std::to_string(views.size()) + " poses, the " + std::to_string(points.size()) + " " + name +
        ".p3d points" + (options.refit_focal ? ", fx fy" : "") +
        (options.refit_principal_point ? ", cx cy" : "") + (options.refit_radial_k1 ? ", k1" : "") +
        (held.empty() ? "" : " (K's" + held + " held at the median)") +
        (k1 != 0 && !options.refit_radial_k1 ? " (k1 held at " + FixedText(k1, 4) + ")" : "") +
        (result.plumb_line
             ? " (k1 from the plumb-line bows of " + std::to_string(result.plumb_line->edges) +
                   " long straight edges of the images, +- " + FixedText(result.plumb_line->k1_sigma, 4) + ")"
             : "") +
        " to the " + std::to_string(observations.size()) + " corner observations of " + name +
        ".nview-corners (Huber 1 px), from the median K and the PnP poses: median reprojection error " +
        FixedText(joint.start_median_px, 3) + " -> " + FixedText(joint.median_px, 3) + " px (per view " +
        RangeText(joint.view_median_px, 2) + "); gauge: the similarity (scale " +
        FixedText(joint.gauge_scale, 4) +
        ") that best maps the refit camera centres onto the P files' centres, which they then miss by " +
        RangeText(joint.centre_offset, 3) + " units";
    if (options.refit_focal || options.refit_principal_point || options.refit_radial_k1 || k1 != 0) {
      refit_note += "; K fx " + FixedText(result.K(0, 0), 2) + " fy " + FixedText(result.K(1, 1), 2) +
                    " cx " + FixedText(result.K(0, 2), 2) + " cy " + FixedText(result.K(1, 2), 2) + " k1 " +
                    FixedText(joint.k1, 4);
    }
    if (options.refit_focal || options.refit_principal_point) {
      k_note = "K: fitted with the poses (next line), started from the " + k_note.substr(3);
    }
    if (!no_plumb_line.empty()) refit_note += "; no plumb-line k1 (" + no_plumb_line + "), k1 = 0";
    LOG(INFO) << "VGG: " << refit_note;
    pose_note = "poses: " + refit_note;
    result.joint_refit = std::move(joint);
  }
  imported.camera.fx = result.K(0, 0);
  imported.camera.fy = result.K(1, 1);
  imported.camera.cx = result.K(0, 2);
  imported.camera.cy = result.K(1, 2);
  for (size_t i = 0; i < views.size(); ++i) {
    ImportedFrame frame{static_cast<double>(i) * kFrameInterval, views[i].image_path,
                        camera_T_world[i].Inverse(), std::nullopt};
    if (options.warp_to_shared_k) frame.source_to_image = result.source_to_image[i];
    imported.frames.push_back(frame);
  }
  imported.notes.push_back("format: VGG multi-view, " + input_dir + ", " + std::to_string(views.size()) +
                           " frames " + views.front().stem + " .. " + views.back().stem);
  imported.notes.push_back(k_note);
  imported.notes.push_back(pose_note);
  imported.notes.push_back(result.world_mirrored
                               ? "world: X_world = -X_file, the point reflection of the files' left-handed frame"
                               : "world: the files' frame");
  imported.notes.push_back("units: those of the VGG reconstruction, not metres (the scale is unknown)");
  imported.notes.push_back("timestamps: 0.1 s per frame (the data set has none)");
  *sequence = std::move(imported);
  *summary = std::move(result);
  return Status::Ok();
}

}  // namespace sfm
