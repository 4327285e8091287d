#include "pipeline/report/report.h"

#include <glog/logging.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "geometry/alignment.h"
#include "geometry/image_undistorter.h"
#include "pipeline/overlay/match_overlay.h"
#include "pipeline/report/assets.h"
#include "pipeline/report/base64.h"
#include "pipeline/report/plot.h"
#include "util/atomic_file.h"
#include "util/parallel.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using plot::Plot;
namespace colour = plot::colour;

constexpr int kPlotWidth = 800, kPlotHeight = 400;
constexpr int kMatchPictures = 3;
constexpr double kPi = 3.14159265358979323846;
const char* const kAxisName[] = {"x", "y", "z"};

// ---- Text ------------------------------------------------------------------------------------

std::string Html(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// printf-style number; "n/a" when not finite (a figure that does not apply).
std::string Num(double value, const char* format = "%.3g") {
  if (!std::isfinite(value)) return "n/a";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

enum class Encoding { kPlot, kPhoto };  // PNG, JPEG

std::string Img(const cv::Mat& image, const std::string& alt, Encoding encoding = Encoding::kPlot) {
  const std::string uri = encoding == Encoding::kPlot ? PngDataUri(image) : JpegDataUri(image);
  return "<img src=\"" + uri + "\" width=\"" + std::to_string(image.cols) + "\" height=\"" +
         std::to_string(image.rows) + "\" alt=\"" + Html(alt) + "\">\n";
}

std::string Figure(const cv::Mat& image, const std::string& alt, const std::string& caption,
                   Encoding encoding = Encoding::kPlot) {
  return "<figure>\n" + Img(image, alt, encoding) + "<figcaption>" + caption + "</figcaption>\n</figure>\n";
}

std::string Note(const std::string& text) { return "<p class=\"note\">" + text + "</p>\n"; }

std::string Row(const std::vector<std::string>& cells, bool header = false) {
  std::string row = "<tr>";
  for (const std::string& cell : cells) row += (header ? "<th>" : "<td>") + cell + (header ? "</th>" : "</td>");
  return row + "</tr>\n";
}

// ---- Geometry --------------------------------------------------------------------------------

std::vector<Eigen::Vector3d> Positions(const std::vector<Pose3>& poses) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(poses.size());
  for (const Pose3& pose : poses) positions.push_back(pose.translation);
  return positions;
}

// The two horizontal axes (a, b) with a x b = vertical, so that the view from above is not mirrored.
std::pair<int, int> HorizontalAxes(int vertical) { return {(vertical + 1) % 3, (vertical + 2) % 3}; }

std::vector<double> Coordinate(const std::vector<Pose3>& poses, int axis) {
  std::vector<double> values;
  for (const Pose3& pose : poses) values.push_back(pose.translation[axis]);
  return values;
}

// The q-quantile (0..1) of values (copied), NaN when empty.
double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::nan("");
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(std::lround(q * (values.size() - 1))));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

double WrapAngle(double angle) {
  angle = std::remainder(angle, 2 * kPi);
  return angle <= -kPi ? angle + 2 * kPi : angle;
}

// ---- Sections --------------------------------------------------------------------------------

struct Context {
  const Sequence& sequence;
  const PipelineResult& result;
  int frames = 0;
  int vertical = 2;
  bool refined = false;  // bundle adjustment ran
  bool truth = false;    // ground truth present
};

std::string SummarySection(const Context& c) {
  const PipelineResult& r = c.result;
  std::string html = "<h2 id=\"summary\">Summary</h2>\n<table>\n";
  int junctions = 0, fewest = 0, most = 0;
  for (size_t i = 0; i < r.junctions.size(); ++i) {
    const int n = static_cast<int>(r.junctions[i].size());
    junctions += n;
    fewest = i == 0 ? n : std::min(fewest, n);
    most = std::max(most, n);
  }
  int matches = 0, consecutive_pairs = 0, consecutive_matches = 0;
  for (const FramePairMatches& pair : r.pairs) {
    matches += static_cast<int>(pair.matches.size());
    if (pair.frame_b == pair.frame_a + 1) ++consecutive_pairs, consecutive_matches += static_cast<int>(pair.matches.size());
  }
  const Camera& camera = c.sequence.calibration.camera;
  html += Row({"frames", std::to_string(c.frames),
               std::to_string(camera.width) + " &times; " + std::to_string(camera.height) + " px, " +
                   (c.truth ? "with ground truth" : "no ground truth")});
  html += Row({"junctions", std::to_string(junctions),
               r.junctions.empty() ? "" :
               Num(double(junctions) / r.junctions.size(), "%.1f") + " per frame (" + std::to_string(fewest) + " to " +
                   std::to_string(most) + ")"});
  html += Row({"matches", std::to_string(matches),
               std::to_string(r.pairs.size()) + " frame pairs; " +
                   (consecutive_pairs > 0 ? Num(double(consecutive_matches) / consecutive_pairs, "%.1f") : "n/a") +
                   " per consecutive pair"});
  html += Row({"tracks", std::to_string(r.tracks.size()), "junctions followed over two or more frames"});
  html += Row({"3D points", std::to_string(r.landmarks.points.size()), "triangulated junctions"});
  html += Row({"3D lines", std::to_string(r.landmarks.lines.size()),
               std::to_string(r.unobservable_lines) + " more dropped as parallel to the motion"});
  html += Row({"wireframe",
               std::to_string(r.wireframe_landmarks.points.size()) + " points, " +
                   std::to_string(r.wireframe_landmarks.lines.size()) + " lines, " +
                   std::to_string(r.wireframe_landmarks.point_edges.size()) + " edges between points",
               "drawn: consistent with their views and well determined (pixel noise " +
                   Num(r.wireframe_selection.pixel_sigma_px, "%.2f") + " px)"});
  html += "</table>\n";

  html += "<h3>Drift against ground truth</h3>\n";
  if (!c.truth || !r.drift_odometry) {
    html += Note("The sequence has no ground truth, so there is no drift to measure.");
  } else {
    const DriftMetrics none{std::nan(""), std::nan(""), std::nan(""), std::nan(""), std::nan("")};
    const DriftMetrics& o = *r.drift_odometry;
    const DriftMetrics& b = r.drift_refined ? *r.drift_refined : none;
    auto rot = [](double rad) { return Num(rad, "%.4f") + " rad (" + Num(rad * 180 / kPi, "%.2f") + "&deg;)"; };
    html += "<table>\n" + Row({"", "odometry", "refined"}, true);
    html += Row({"ATE (position RMSE after SE(3) alignment)", Num(o.ate_m, "%.4f") + " m", Num(b.ate_m, "%.4f") + " m"});
    html += Row({"ATE after a similarity (the shape without the scale one camera cannot see)",
                 Num(o.ate_sim3_m, "%.4f") + " m", Num(b.ate_sim3_m, "%.4f") + " m"});
    html += Row({"scale that similarity applies (above 1: the trajectory is too short)", Num(o.sim3_scale, "%.4f"),
                 Num(b.sim3_scale, "%.4f")});
    html += Row({"RPE translation per frame (RMSE)", Num(o.rpe_trans_m, "%.4f") + " m", Num(b.rpe_trans_m, "%.4f") + " m"});
    html += Row({"RPE rotation per frame (RMSE)", rot(o.rpe_rot_rad), rot(b.rpe_rot_rad)});
    html += "</table>\n";
    if (!r.drift_refined) html += Note("Bundle adjustment did not run: there is no refined trajectory.");
  }

  const TrajectoryEvidence& e = r.evidence;
  if (e.computed) {
    html += "<h3>Quality without ground truth</h3>\n<table>\n" + Row({"", "odometry", "initial", "refined"}, true);
    html += Row({"the matches' epipolar fit (median over the pairs of their median Sampson distance)",
                 Num(e.epipolar_px_odometry, "%.2f") + " px", Num(e.epipolar_px_initial, "%.2f") + " px",
                 Num(e.epipolar_px_refined, "%.2f") + " px"});
    html += "</table>\n<table>\n";
    html += Row({"reprojection RMS after the adjustment", Num(e.point_rms_px, "%.2f") + " px (points), " +
                                                              Num(e.line_rms_px, "%.2f") + " px (lines)"});
    html += Row({"image pairs with a relative pose", std::to_string(r.initialization.pairs.constraints) + " of " +
                                                         std::to_string(r.initialization.pairs.pairs)});
    std::string loops = std::to_string(r.initialization.loops.size()) + " of " +
                        std::to_string(r.initialization.loop_candidates) + " candidate pairs";
    for (size_t i = 0; i < r.initialization.loops.size(); ++i) {
      const std::array<int, 3>& loop = r.initialization.loops[i];
      loops += (i ? ", " : ": ") + std::string("frames ") + std::to_string(loop[0]) + "-" + std::to_string(loop[1]) +
               " (" + std::to_string(loop[2]) + " inliers)";
    }
    html += Row({"loops closed", loops});
    html += Row({"camera centres moved from the odometry", Num(e.moved_from_odometry_median_m, "%.3f") +
                                                               " m median, " +
                                                               Num(e.moved_from_odometry_max_m, "%.3f") + " m at most"});
    html += Row({"refined steps beyond 3 sigma of the odometry's noise",
                 std::to_string(e.frames_disagreeing_with_odometry.size())});
    html += Row({"bundle adjustment", e.adjustment_converged ? "converged" : "stopped at its iteration limit"});
    html += "</table>\n";
    for (const std::string& warning : e.warnings) html += Note("Warning: " + warning + ".");
  }

  const StageTimes& t = r.times;
  html += "<h3>Stage times</h3>\n<table>\n" + Row({"stage", "wall time"}, true);
  html += Row({"front end (segments, junctions)", Num(t.frontend, "%.2f") + " s"});
  html += Row({"matching", Num(t.matching, "%.2f") + " s"});
  html += Row({"back end (tracks, triangulation, bundle adjustment)", Num(t.backend, "%.2f") + " s"});
  html += Row({"<b>total</b>", "<b>" + Num(t.total, "%.2f") + " s</b>"});
  return html + "</table>\n";
}

std::string TrajectorySection(const Context& c) {
  const PipelineResult& r = c.result;
  const auto [a, b] = HorizontalAxes(c.vertical);
  Plot figure(kPlotWidth, kPlotHeight);
  figure.SetTitle("camera trajectories seen from above");
  figure.SetXLabel(std::string(kAxisName[a]) + " [m]");
  figure.SetYLabel(std::string(kAxisName[b]) + " [m]");
  figure.SetEqualAspect(true);
  // Ground truth as a wide grey band under the estimates, so that an estimate on top of it still shows both.
  if (c.truth) figure.AddLine(Coordinate(*r.world_T_camera_truth, a), Coordinate(*r.world_T_camera_truth, b),
                              colour::kGrey, "ground truth", 6);
  figure.AddLine(Coordinate(r.world_T_camera_odometry, a), Coordinate(r.world_T_camera_odometry, b), colour::kOrange,
                 "odometry", 2);
  if (c.refined) figure.AddLine(Coordinate(r.world_T_camera_refined, a), Coordinate(r.world_T_camera_refined, b),
                                colour::kBlue, "refined (bundle adjustment)", 2);
  const std::vector<Pose3>& first = c.truth ? *r.world_T_camera_truth : r.world_T_camera_odometry;
  if (!first.empty()) {
    figure.AddMarkers({first.front().translation[a]}, {first.front().translation[b]}, colour::kGreen, "start", 5);
  }
  return "<h2 id=\"trajectories\">Trajectories</h2>\n" +
         Figure(figure.Render(), "trajectories from above",
                "Camera positions (trajectory_*.txt) in the output world frame, as written (not aligned), seen "
                "from above: " + std::string(kAxisName[a]) + " to the right, " + kAxisName[b] + " up, " +
                kAxisName[c.vertical] + " towards the viewer.");
}

std::string ErrorSection(const Context& c) {
  const PipelineResult& r = c.result;
  std::string html = "<h2 id=\"errors\">Position and heading error</h2>\n";
  if (!c.truth) return html + Note("The sequence has no ground truth (no groundtruth.txt), so these errors are not known.");
  std::vector<double> frames(c.frames);
  std::iota(frames.begin(), frames.end(), 0.0);
  const TrajectoryErrors odometry = ComputeTrajectoryErrors(r.world_T_camera_odometry, *r.world_T_camera_truth, c.vertical);
  TrajectoryErrors refined;
  if (c.refined) refined = ComputeTrajectoryErrors(r.world_T_camera_refined, *r.world_T_camera_truth, c.vertical);

  Plot position(kPlotWidth, kPlotHeight);
  position.SetTitle("position error against ground truth");
  position.SetXLabel("frame");
  position.SetYLabel("position error [m]");
  position.SetYFromZero(true);
  position.SetIntegerX(true);
  position.AddLine(frames, odometry.position_m, colour::kOrange, "odometry", 2);
  if (c.refined) position.AddLine(frames, refined.position_m, colour::kBlue, "refined", 2);

  auto degrees = [](std::vector<double> radians) {
    for (double& v : radians) v *= 180 / kPi;
    return radians;
  };
  Plot heading(kPlotWidth, kPlotHeight);
  heading.SetTitle("heading error against ground truth");
  heading.SetXLabel("frame");
  heading.SetYLabel("heading error [deg]");
  heading.SetIntegerX(true);
  heading.AddLine(frames, degrees(odometry.heading_rad), colour::kOrange, "odometry", 2);
  if (c.refined) heading.AddLine(frames, degrees(refined.heading_rad), colour::kBlue, "refined", 2);

  html += Note("Each estimated trajectory is first aligned to the ground truth by the rigid SE(3) transform "
               "that the ATE uses (AlignSE3 of the camera positions, docs/metrics.md); the RMSE of the position "
               "error is the ATE. Heading error: the angle about the vertical (" + std::string(kAxisName[c.vertical]) +
               ") axis from the true to the estimated viewing direction, positive counter-clockwise seen from above.");
  html += Figure(position.Render(), "position error per frame", "Position error per frame, metres.");
  html += Figure(heading.Render(), "heading error per frame", "Heading error per frame, degrees.");
  return html;
}

std::string JunctionSection(const Context& c) {
  std::vector<double> counts;
  for (const Junctions& junctions : c.result.junctions) counts.push_back(static_cast<double>(junctions.size()));
  Plot figure(kPlotWidth, kPlotHeight);
  figure.SetTitle("junctions detected per frame");
  figure.SetXLabel("frame");
  figure.SetYLabel("junctions");
  figure.SetIntegerX(true);
  figure.AddBars(counts, colour::kBlue, "");
  return "<h2 id=\"junctions\">Junctions per frame</h2>\n" +
         Figure(figure.Render(), "junctions per frame", "Junctions detected in each frame (junctions/NNNNNN.json).");
}

std::string MatchSection(const Context& c) {
  // Pairs (a, a + 1) and (a, a + 2), each a bar series over a.
  std::vector<double> gap1(std::max(c.frames - 1, 0), std::nan("")), gap2(std::max(c.frames - 2, 0), std::nan(""));
  int other = 0;
  for (const FramePairMatches& pair : c.result.pairs) {
    const double n = static_cast<double>(pair.matches.size());
    const int gap = pair.frame_b - pair.frame_a;
    if (gap == 1 && pair.frame_a >= 0 && pair.frame_a < static_cast<int>(gap1.size())) gap1[pair.frame_a] = n;
    else if (gap == 2 && pair.frame_a >= 0 && pair.frame_a < static_cast<int>(gap2.size())) gap2[pair.frame_a] = n;
    else ++other;
  }
  Plot figure(kPlotWidth, kPlotHeight);
  figure.SetTitle("junction matches per frame pair");
  figure.SetXLabel("first frame i of the pair");
  figure.SetYLabel("matches");
  figure.SetIntegerX(true);
  figure.AddBars(gap1, colour::kBlue, "frames i, i+1");
  if (std::any_of(gap2.begin(), gap2.end(), [](double v) { return std::isfinite(v); })) {
    figure.AddBars(gap2, colour::kSky, "frames i, i+2");
  }
  std::string html = "<h2 id=\"matches\">Matches per frame pair</h2>\n" +
                     Figure(figure.Render(), "matches per frame pair",
                            "Junction matches of each matched pair of frames (matches/NNNNNN_MMMMMM.csv).");
  if (other > 0) html += Note(std::to_string(other) + " other pairs are not shown.");
  return html;
}

// Match pictures of larger frames are drawn on the frames shrunk to this width (pixels), so the
// page stays a few megabytes and quick to write whatever the camera (8000x6000 frames at full
// size make a 60 MB page whose encoding takes longer than the rest of the run), and the junction
// numbers stay readable.
constexpr int kMaxPictureWidth = 960;

// The factor a frame of this width is shrunk by for its picture (1: not shrunk).
double PictureScale(int width) {
  return width > kMaxPictureWidth ? static_cast<double>(kMaxPictureWidth) / width : 1;
}

cv::Mat Shrunk(const cv::Mat& image, double f) {
  if (f == 1) return image;
  cv::Mat small;
  cv::resize(
      image, small,
      cv::Size(static_cast<int>(std::lround(image.cols * f)), static_cast<int>(std::lround(image.rows * f))),
      0, 0, cv::INTER_AREA);
  return small;
}

// Pixel centres scale about the image's corner (the centre of the top-left pixel is at (0, 0),
// conventions.md).
Eigen::Vector2d ShrunkPixel(const Eigen::Vector2d& p, double f) {
  return Eigen::Vector2d((p.array() + 0.5) * f - 0.5);
}

// The camera of the frames shrunk by f (the distortion acts on normalised coordinates: unchanged).
Camera ShrunkCamera(const Camera& camera, double f, const cv::Size& size) {
  Camera small = camera;
  small.width = size.width;
  small.height = size.height;
  small.fx *= f;
  small.fy *= f;
  const Eigen::Vector2d c = ShrunkPixel(Eigen::Vector2d(camera.cx, camera.cy), f);
  small.cx = c.x();
  small.cy = c.y();
  return small;
}

Junctions Shrunk(const Junctions& junctions, double f) {
  if (f == 1) return junctions;
  Junctions shrunk = junctions;
  for (Junction& junction : shrunk) {
    junction.location = ShrunkPixel(junction.location, f);
    for (JunctionSegment& segment : junction.segments) segment.end = ShrunkPixel(segment.end, f);
  }
  return shrunk;
}

std::string MatchPictureSection(const Context& c, const std::vector<cv::Mat>& images,
                                const std::vector<cv::Mat>& stored_images) {
  std::string html = "<h2 id=\"match-images\">Match pictures</h2>\n";
  std::vector<const FramePairMatches*> consecutive;
  for (const FramePairMatches& pair : c.result.pairs) {
    if (pair.frame_b == pair.frame_a + 1) consecutive.push_back(&pair);
  }
  if (consecutive.empty()) return html + Note("No consecutive pair of frames was matched.");
  // A few pairs spread over the sequence: the first, the last and evenly between.
  std::vector<const FramePairMatches*> shown;
  const int n = static_cast<int>(consecutive.size());
  for (int k = 0; k < std::min(kMatchPictures, n); ++k) {
    const int index = kMatchPictures == 1 || n == 1 ? 0 : static_cast<int>(std::lround(double(k) * (n - 1) / (std::min(kMatchPictures, n) - 1)));
    if (shown.empty() || shown.back() != consecutive[index]) shown.push_back(consecutive[index]);
  }
  html += Note("As in Fig. 6 of the paper: the earlier frame left, the later right. Matched junctions carry the "
               "same number in both frames and corresponding junction segments the same colour; unmatched "
               "junctions are thin and grey. Undistorted images, shown dimmed.");

  // Each shown frame at picture scale, undistorted: given, or from the stored frames (given or read
  // again), shrunk before the undistortion (a 48-megapixel remap would cost more than the rest).
  // The frames are read, and the pictures drawn and encoded, in parallel; joined in order.
  const double f = PictureScale(c.sequence.calibration.camera.width);
  std::vector<int> frames;  // distinct, in order of first use
  for (const FramePairMatches* pair : shown) {
    for (const int frame : {pair->frame_a, pair->frame_b}) {
      if (std::find(frames.begin(), frames.end(), frame) == frames.end()) frames.push_back(frame);
    }
  }
  std::vector<cv::Mat> pictures(frames.size());
  std::vector<Status> statuses(frames.size(), Status::Ok());
  ParallelFor(static_cast<int>(frames.size()), [&](int k) {
    if (!images.empty()) {
      pictures[k] = Shrunk(images.at(frames[k]), f);
      return;
    }
    cv::Mat grey;
    if (!stored_images.empty()) {
      grey = stored_images.at(frames[k]);
    } else {
      statuses[k] = LoadFrameImage(c.sequence, frames[k], &grey);
      if (!statuses[k].ok()) return;
    }
    pictures[k] = Shrunk(grey, f);
  });
  if (images.empty()) {
    const auto first = std::find_if(statuses.begin(), statuses.end(), [](const Status& s) { return s.ok(); });
    if (first != statuses.end()) {
      const ImageUndistorter undistorter(
          ShrunkCamera(c.sequence.calibration.camera, f, pictures[first - statuses.begin()].size()));
      ParallelFor(static_cast<int>(frames.size()), [&](int k) {
        if (statuses[k].ok()) pictures[k] = undistorter.Apply(pictures[k]);
      });
    }
  }
  auto slot = [&](int frame) { return std::find(frames.begin(), frames.end(), frame) - frames.begin(); };
  std::vector<std::string> figures(shown.size());
  ParallelFor(static_cast<int>(shown.size()), [&](int s) {
    const FramePairMatches* pair = shown[s];
    const auto ka = slot(pair->frame_a), kb = slot(pair->frame_b);
    const Status& status = statuses[ka].ok() ? statuses[kb] : statuses[ka];
    if (!status.ok()) {
      figures[s] = Note("Frames " + std::to_string(pair->frame_a) + " and " + std::to_string(pair->frame_b) +
                        ": no picture, the image could not be read (" + Html(status.message()) + ").");
      return;
    }
    const cv::Mat& image_a = pictures[ka];
    const cv::Mat& image_b = pictures[kb];
    const Junctions& a = c.result.junctions.at(pair->frame_a);
    const Junctions& b = c.result.junctions.at(pair->frame_b);
    const int scale = image_a.cols < 400 ? 2 : 1;  // small images enlarged so that the numbers stay readable
    const cv::Mat picture =
        DrawMatchOverlay(image_a, Shrunk(a, f), image_b, Shrunk(b, f), pair->matches, scale);
    figures[s] = Figure(picture, "matches between frames " + std::to_string(pair->frame_a) + " and " + std::to_string(pair->frame_b),
                        "Frames " + std::to_string(pair->frame_a) + " (left) and " + std::to_string(pair->frame_b) +
                            " (right): " + std::to_string(pair->matches.size()) + " matches of " + std::to_string(a.size()) +
                            " and " + std::to_string(b.size()) + " junctions.",
                        Encoding::kPhoto);
  });
  for (const std::string& figure : figures) html += figure;
  return html;
}

// The wireframe's view directions: up from the robot's base frame (UpDirection); `length` the
// horizontal direction of the map's edges (their directions modulo 90 degrees averaged as 4 theta,
// weighted by horizontal length: a man-made scene's walls), of the two perpendicular ones the one
// along which the drawn coordinates spread more, turned to run with the camera path; `across` =
// up x length (so that the view from above is not mirrored).
struct ViewAxes {
  Eigen::Vector3d length, across, up;
};

ViewAxes WireframeAxes(const Context& c, const std::vector<Eigen::Vector3d>& drawn,
                       const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& edges) {
  const std::vector<Pose3>& cameras =
      c.refined ? c.result.world_T_camera_refined : c.result.world_T_camera_odometry;
  ViewAxes axes;
  axes.up = UpDirection(cameras, c.sequence.calibration.base_T_camera);
  const Eigen::Vector3d e1 = axes.up.unitOrthogonal(), e2 = axes.up.cross(e1);  // any horizontal basis
  // The mean of 4 theta, then again over the edges within 5 degrees of it (modulo 90), so that
  // oblique edges do not pull it.
  double theta = 0;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Vector2d sum4 = Eigen::Vector2d::Zero();
    for (const auto& [a, b] : edges) {
      const Eigen::Vector2d d((b - a).dot(e1), (b - a).dot(e2));
      const double angle = std::atan2(d.y(), d.x());
      if (pass == 1 && std::abs(WrapAngle(4 * (angle - theta))) > 4 * kPi / 36) continue;
      sum4 += d.norm() * Eigen::Vector2d(std::cos(4 * angle), std::sin(4 * angle));
    }
    if (sum4.norm() > 0) theta = std::atan2(sum4.y(), sum4.x()) / 4;
  }
  const Eigen::Vector3d first = std::cos(theta) * e1 + std::sin(theta) * e2;
  const Eigen::Vector3d second = axes.up.cross(first);
  auto spread = [&](const Eigen::Vector3d& direction) {
    std::vector<double> values;
    for (const Eigen::Vector3d& p : drawn) values.push_back(p.dot(direction));
    return values.empty() ? 0.0 : Quantile(values, 0.98) - Quantile(values, 0.02);
  };
  axes.length = spread(first) >= spread(second) ? first : second;
  if (cameras.size() >= 2 &&
      (cameras.back().translation - cameras.front().translation).dot(axes.length) < 0) {
    axes.length = -axes.length;
  }
  axes.across = axes.up.cross(axes.length);
  return axes;
}

// An orthographic view of the wireframe onto the plane of the directions h (to the right) and v
// (up): 3D lines and edges between points as segments, 3D points as dots, the camera path, and a
// scale bar.
cv::Mat WireframeView(const Context& c, const Eigen::Vector3d& h, const Eigen::Vector3d& v,
                      const std::string& title, const std::string& h_label, const std::string& v_label) {
  const Landmarks& landmarks = c.result.wireframe_landmarks;  // what wireframe.ply holds
  const std::vector<Pose3>& cameras = c.refined ? c.result.world_T_camera_refined : c.result.world_T_camera_odometry;
  std::vector<std::array<double, 4>> segments;
  std::vector<double> hs, vs;  // every drawn coordinate, for the range
  auto add_segment = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    segments.push_back({a.dot(h), a.dot(v), b.dot(h), b.dot(v)});
    hs.push_back(a.dot(h)), hs.push_back(b.dot(h)), vs.push_back(a.dot(v)), vs.push_back(b.dot(v));
  };
  for (const LineLandmark& line : landmarks.lines) add_segment(line.end0, line.end1);
  for (const auto& [a, b] : landmarks.point_edges)
    add_segment(landmarks.points[a].position, landmarks.points[b].position);
  std::vector<double> px, py, cam_h, cam_v;
  for (const PointLandmark& point : landmarks.points) {
    px.push_back(point.position.dot(h)), py.push_back(point.position.dot(v));
    hs.push_back(px.back()), vs.push_back(py.back());
  }
  for (const Pose3& camera : cameras)
    cam_h.push_back(camera.translation.dot(h)), cam_v.push_back(camera.translation.dot(v));
  Plot figure(kPlotWidth, kPlotHeight);
  figure.SetTitle(title);
  figure.SetXLabel(h_label + " [m]");
  figure.SetYLabel(v_label + " [m]");
  figure.SetEqualAspect(true);
  figure.SetScaleBar("m");
  figure.AddLine(cam_h, cam_v, colour::kOrange, c.refined ? "cameras (refined)" : "cameras (odometry)",
                 2);  // under the map
  figure.AddSegments(segments, colour::kBlue, "3D lines and edges", 1);
  figure.AddMarkers(px, py, colour::kVermillion, "3D points", 2);
  // The range of the bulk of the map (2 % to 98 %, widened by a tenth) and the cameras, so that a
  // few far-off end-points do not shrink everything else; what lies outside is clipped.
  auto range = [&](const std::vector<double>& values, const std::vector<double>& path, double* lo,
                   double* hi) {
    *lo = Quantile(values, 0.02), *hi = Quantile(values, 0.98);
    const double pad = 0.1 * (*hi - *lo);
    *lo -= pad, *hi += pad;
    for (const double x : path) *lo = std::min(*lo, x), *hi = std::max(*hi, x);
    if (!(*hi - *lo > 1e-6)) *lo -= 0.5, *hi += 0.5;
  };
  double lo, hi;
  if (!hs.empty()) {
    range(hs, cam_h, &lo, &hi);
    figure.SetXRange(lo, hi);
    range(vs, cam_v, &lo, &hi);
    figure.SetYRange(lo, hi);
  }
  return figure.Render();
}

// ---- The 3D view -----------------------------------------------------------------------------

constexpr int kMostFrusta = 60;  // more would hide the map; every k-th camera beyond that

std::string HexColour(const cv::Scalar& bgr) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", int(bgr[2]), int(bgr[1]), int(bgr[0]));
  return text;
}

std::string JsonNumbers(const std::vector<double>& values) {
  std::string json = "[";
  for (size_t i = 0; i < values.size(); ++i) {
    json += (i ? "," : "") + (std::isfinite(values[i]) ? Num(values[i], "%.6g") : std::string("null"));
  }
  return json + "]";
}

std::string JsonVector(const Eigen::Vector3d& v) { return JsonNumbers({v.x(), v.y(), v.z()}); }

void Append(std::vector<double>* flat, const Eigen::Vector3d& p) {
  flat->insert(flat->end(), {p.x(), p.y(), p.z()});
}

// The module text with every `specifier` turned to `replacement`; CHECKs that there was one.
std::string Reimported(std::string text, const std::string& specifier, const std::string& replacement) {
  size_t replaced = 0;
  for (size_t at = text.find(specifier); at != std::string::npos;
       at = text.find(specifier, at + replacement.size())) {
    text.replace(at, specifier.size(), replacement);
    ++replaced;
  }
  CHECK_GT(replaced, 0u) << "the vendored three.js no longer imports " << specifier;
  return text;
}

// A data: URL of a JavaScript module for the page's import map: percent-encoded where a URL, the
// JSON string or the HTML <script> element around it would read the character otherwise (RFC 3986),
// the rest as it is (a third smaller than base64 on minified code).
std::string ModuleDataUrl(const std::string& text) {
  static const std::string kKept = "-_.!~*'();/?:@&=+$,{}[]|^";
  std::string url = "data:text/javascript;charset=utf-8,";
  url.reserve(url.size() + text.size() * 11 / 10);
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || kKept.find(c) != std::string::npos) {
      url += c;
    } else {
      char escaped[4];
      std::snprintf(escaped, sizeof(escaped), "%%%02X", u);
      url += escaped;
    }
  }
  return url;
}

// The import map that lets the viewer's `import ... from 'three'` find the inlined three.js: the
// module build's relative import of its core becomes the bare name "three/core".
std::string ThreeImportMap() {
  const std::string module =
      Reimported(report_assets::kThreeModule, "\"./three.core.min.js\"", "\"three/core\"");
  return "<script type=\"importmap\">{\"imports\":{\"three/core\":\"" +
         ModuleDataUrl(report_assets::kThreeCore) + "\",\n\"three\":\"" + ModuleDataUrl(module) +
         "\",\n\"three/addons/controls/OrbitControls.js\":\"" + ModuleDataUrl(report_assets::kOrbitControls) +
         "\"}}</script>\n";
}

// The scene of the 3D view as JSON (read by view3d.js): the wireframe.ply points and edges, the
// trajectories, the frusta of the drawn cameras (refined, else odometry), and a frame to look at it
// in: the bulk of the map (2nd to 98th percentile per axis, as in the static views) and every camera.
std::string View3dSceneJson(const Context& c, const ViewAxes& axes) {
  const PipelineResult& r = c.result;
  const Landmarks& landmarks = r.wireframe_landmarks;
  std::vector<double> points, edges;
  std::array<std::vector<double>, 3> coordinates;
  for (const PointLandmark& p : landmarks.points) {
    Append(&points, p.position);
    for (int k = 0; k < 3; ++k) coordinates[k].push_back(p.position[k]);
  }
  auto add_edge = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    Append(&edges, a), Append(&edges, b);
    for (int k = 0; k < 3; ++k) coordinates[k].push_back(a[k]), coordinates[k].push_back(b[k]);
  };
  for (const LineLandmark& line : landmarks.lines) add_edge(line.end0, line.end1);
  for (const auto& [a, b] : landmarks.point_edges)
    add_edge(landmarks.points[a].position, landmarks.points[b].position);

  const std::vector<Pose3>& cameras = c.refined ? r.world_T_camera_refined : r.world_T_camera_odometry;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int k = 0; k < 3; ++k) {
    if (!coordinates[k].empty())
      lo[k] = Quantile(coordinates[k], 0.02), hi[k] = Quantile(coordinates[k], 0.98);
  }
  for (const Pose3& camera : cameras)
    lo = lo.cwiseMin(camera.translation), hi = hi.cwiseMax(camera.translation);
  const Eigen::Vector3d centre = (lo + hi) / 2;
  const double radius = std::max(0.5 * (hi - lo).norm(), 0.1);

  struct Path {
    const char* name;
    const std::vector<Pose3>* poses;
    cv::Scalar colour;
  };
  std::vector<Path> paths;
  if (c.truth) paths.push_back({"ground truth", &*r.world_T_camera_truth, colour::kGrey});
  paths.push_back({"odometry", &r.world_T_camera_odometry, colour::kOrange});
  if (c.refined) paths.push_back({"refined", &r.world_T_camera_refined, colour::kGreen});
  std::string json = "{\"centre\":" + JsonVector(centre) + ",\"radius\":" + Num(radius, "%.6g") +
                     ",\"up\":" + JsonVector(axes.up) + ",\"along\":" + JsonVector(axes.length) +
                     ",\"across\":" + JsonVector(axes.across) + ",\n\"colours\":{\"edges\":\"" +
                     HexColour(colour::kBlue) + "\",\"points\":\"" + HexColour(colour::kVermillion) +
                     "\"},\n\"points\":" + JsonNumbers(points) + ",\n\"edges\":" + JsonNumbers(edges) +
                     ",\n\"paths\":[";
  for (size_t i = 0; i < paths.size(); ++i) {
    std::vector<double> xyz;
    for (const Pose3& pose : *paths[i].poses) Append(&xyz, pose.translation);
    json += std::string(i ? ",\n" : "") + "{\"name\":\"" + paths[i].name + "\",\"colour\":\"" +
            HexColour(paths[i].colour) + "\",\"xyz\":" + JsonNumbers(xyz) + "}";
  }
  // A frustum: the centre to the four image corners at depth d, and the corners' rectangle; d is
  // 0.8 times the median distance between the frusta drawn, so that they do not overlap, within
  // 1/60 and 1/15 of the map's size.
  const Camera& intrinsics = c.sequence.calibration.camera;
  const int step = std::max(1, static_cast<int>(std::ceil(cameras.size() / double(kMostFrusta))));
  std::vector<double> gaps;
  for (size_t i = step; i < cameras.size(); i += step) {
    gaps.push_back((cameras[i].translation - cameras[i - step].translation).norm());
  }
  const double depth =
      gaps.empty() ? radius / 15 : std::clamp(0.8 * Quantile(gaps, 0.5), radius / 60, radius / 15);
  std::vector<double> frusta;
  const bool has_intrinsics = intrinsics.fx > 0 && intrinsics.fy > 0;
  for (size_t i = 0; has_intrinsics && i < cameras.size(); i += step) {
    std::array<Eigen::Vector3d, 4> corner;
    const double us[] = {0, double(intrinsics.width), double(intrinsics.width), 0};
    const double vs[] = {0, 0, double(intrinsics.height), double(intrinsics.height)};
    for (int k = 0; k < 4; ++k) {
      corner[k] = cameras[i] * (depth * Eigen::Vector3d((us[k] - intrinsics.cx) / intrinsics.fx,
                                                        (vs[k] - intrinsics.cy) / intrinsics.fy, 1));
    }
    for (int k = 0; k < 4; ++k) {
      Append(&frusta, cameras[i].translation), Append(&frusta, corner[k]);
      Append(&frusta, corner[k]), Append(&frusta, corner[(k + 1) % 4]);
    }
  }
  return json + "],\n\"frusta\":{\"colour\":\"" + HexColour(c.refined ? colour::kGreen : colour::kOrange) +
         "\",\"xyz\":" + JsonNumbers(frusta) + "}}";
}

std::string View3d(const Context& c, const ViewAxes& axes) {
  auto key = [](const cv::Scalar& colour, const std::string& label) {
    return "<span style=\"color:" + HexColour(colour) + "\">&#9632;</span>&nbsp;" + label;
  };
  std::string legend = key(colour::kBlue, "edges") + ", " + key(colour::kVermillion, "points") + ", " +
                       (c.truth ? key(colour::kGrey, "ground truth") + ", " : "") +
                       key(colour::kOrange, "odometry") +
                       (c.refined ? ", " + key(colour::kGreen, "refined") : "") + "; camera frusta on the " +
                       (c.refined ? "refined" : "odometry") + " poses";
  return "<h3 id=\"view3d-title\">In 3D</h3>\n" +
         Note("Left drag turns the view, the wheel zooms, right drag (or shift and left drag) moves it. " +
              legend + ". <button id=\"view3d-reset\" type=\"button\">reset view</button>") +
         "<div id=\"view3d\" style=\"border:1px solid #ddd\">" +
         Note("The 3D view needs a browser with JavaScript modules and WebGL.") + "</div>\n" +
         Note("Drawn with three.js " + std::string(report_assets::kThreeVersion) +
              " (MIT licence), inlined.") +
         "<script type=\"application/json\" id=\"view3d-scene\">" + View3dSceneJson(c, axes) + "</script>\n" +
         ThreeImportMap() + "<script type=\"module\">\n" + report_assets::kViewer + "\n</script>\n";
}

std::string WireframeSection(const Context& c) {
  const Landmarks& landmarks = c.result.wireframe_landmarks;  // what wireframe.ply holds
  std::string html = "<h2 id=\"wireframe\">Wireframe</h2>\n";
  if (landmarks.lines.empty() && landmarks.points.empty()) {
    return html + Note("No 3D point or line was reconstructed, so there is no wireframe to show.");
  }
  std::vector<Eigen::Vector3d> drawn;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> edges;
  for (const PointLandmark& p : landmarks.points) drawn.push_back(p.position);
  for (const LineLandmark& l : landmarks.lines) {
    drawn.push_back(l.end0), drawn.push_back(l.end1);
    edges.emplace_back(l.end0, l.end1);
  }
  for (const auto& [a, b] : landmarks.point_edges)
    edges.emplace_back(landmarks.points[a].position, landmarks.points[b].position);
  const ViewAxes axes = WireframeAxes(c, drawn, edges);
  html += Note(
      "The 3D lines, edges and points of wireframe.ply projected orthographically, with the camera path; " +
      std::to_string(landmarks.lines.size() + landmarks.point_edges.size()) + " edges (" +
      std::to_string(landmarks.point_edges.size()) + " between points joined in the images), " +
      std::to_string(landmarks.points.size()) +
      " points. Up is the robot base's (its z axis; the cameras' up where the data set gives camera "
      "poses), so the floor is down; to the right, the direction of the map's edges along which it is "
      "longer, with the camera path. Framed on the bulk of the map (2nd to 98th percentile); what lies "
      "further out is "
      "cut off.");
  html += Figure(
      WireframeView(c, axes.length, axes.across, "wireframe seen from above", "along the map", "across"),
      "wireframe from above", "From above: the map's length to the right, across it up.");
  html += Figure(
      WireframeView(c, axes.length, axes.up, "wireframe seen from the side", "along the map", "height"),
      "wireframe from the side", "From the side: the map's length to the right, up (gravity) up.");
  return html + View3d(c, axes);
}

constexpr char kStyle[] =
    "body{font-family:sans-serif;color:#222;max-width:1320px;margin:1.5em auto;padding:0 1em;line-height:1.4}\n"
    "h1{font-size:1.5em;margin-bottom:.2em}\n"
    "h2{font-size:1.2em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.8em}\n"
    "h3{font-size:1em;margin-top:1.2em}\n"
    "table{border-collapse:collapse;margin:.5em 0}\n"
    "th,td{padding:.2em .9em;border-bottom:1px solid #e4e4e4;text-align:left}\n"
    "th{background:#f4f4f4}\n"
    "figure{margin:1em 0}\n"
    "img{display:block;max-width:100%;height:auto;border:1px solid #ddd}\n"
    "figcaption,.note{color:#555;font-size:.9em}\n"
    "nav a{margin-right:1em}\n";

}  // namespace

namespace {

// "data:image/<type>;base64,..." of the image encoded by OpenCV as `extension` with `parameters`.
std::string EncodedDataUri(const cv::Mat& image, const char* extension, const char* type,
                           const std::vector<int>& parameters = {}) {
  std::vector<uchar> bytes;
  CHECK(cv::imencode(extension, image, bytes, parameters)) << type << " encoding failed";
  return std::string("data:image/") + type + ";base64," +
         Base64Encode(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

std::string PngDataUri(const cv::Mat& image) { return EncodedDataUri(image, ".png", "png"); }

std::string JpegDataUri(const cv::Mat& image) {
  return EncodedDataUri(image, ".jpg", "jpeg", {cv::IMWRITE_JPEG_QUALITY, kPhotoJpegQuality});
}

Eigen::Vector3d UpDirection(const std::vector<Pose3>& world_T_camera, const Pose3& base_T_camera) {
  const bool rig_is_identity = base_T_camera.translation.norm() < 1e-12 &&
                               base_T_camera.rotation.angularDistance(Eigen::Quaterniond::Identity()) < 1e-9;
  const Eigen::Vector3d up_in_base = rig_is_identity ? Eigen::Vector3d(0, -1, 0) : Eigen::Vector3d(0, 0, 1);
  const Pose3 camera_T_base = base_T_camera.Inverse();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Pose3& pose : world_T_camera) sum += (pose * camera_T_base).RotationMatrix() * up_in_base;
  return sum.norm() > 1e-9 ? Eigen::Vector3d(sum.normalized()) : Eigen::Vector3d::UnitZ();
}

int VerticalAxis(const std::vector<Pose3>& world_T_camera) {
  if (world_T_camera.empty()) return 2;
  Eigen::Vector3d lo = world_T_camera.front().translation, hi = lo;
  for (const Pose3& pose : world_T_camera) {
    lo = lo.cwiseMin(pose.translation);
    hi = hi.cwiseMax(pose.translation);
  }
  const Eigen::Vector3d spread = hi - lo;
  Eigen::Index least = 0;
  spread.minCoeff(&least);
  if (spread.z() <= 0.05 || spread.z() <= spread[least]) return 2;
  return static_cast<int>(least);
}

TrajectoryErrors ComputeTrajectoryErrors(const std::vector<Pose3>& world_T_camera_estimated,
                                         const std::vector<Pose3>& world_T_camera_truth, int vertical_axis) {
  CHECK_EQ(world_T_camera_estimated.size(), world_T_camera_truth.size());
  CHECK(vertical_axis >= 0 && vertical_axis < 3);
  TrajectoryErrors errors;
  if (world_T_camera_truth.empty()) return errors;
  const Pose3 truth_T_estimated = AlignSE3(Positions(world_T_camera_estimated), Positions(world_T_camera_truth));
  const auto [a, b] = HorizontalAxes(vertical_axis);
  // The camera axis whose heading is measured: the optical axis, unless it is nearly vertical.
  const Eigen::Vector3d optical = world_T_camera_truth.front().RotationMatrix().col(2);
  const int camera_axis = std::abs(optical[vertical_axis]) > std::cos(kPi / 6) ? 0 : 2;
  auto heading = [&](const Eigen::Quaterniond& rotation) {
    const Eigen::Vector3d d = rotation.toRotationMatrix().col(camera_axis);
    return std::atan2(d[b], d[a]);
  };
  for (size_t i = 0; i < world_T_camera_truth.size(); ++i) {
    const Pose3 aligned = truth_T_estimated * world_T_camera_estimated[i];
    errors.position_m.push_back((aligned.translation - world_T_camera_truth[i].translation).norm());
    errors.heading_rad.push_back(WrapAngle(heading(aligned.rotation) - heading(world_T_camera_truth[i].rotation)));
  }
  return errors;
}

std::string ReportHtml(const Sequence& sequence, const PipelineResult& result,
                       const std::vector<cv::Mat>& undistorted_images_or_empty,
                       const std::vector<cv::Mat>& stored_images_or_empty) {
  const std::vector<cv::Mat>& images = undistorted_images_or_empty;
  CHECK(images.empty() || images.size() == sequence.frames.size())
      << "give one undistorted image per frame, or none";
  Context c{sequence, result};
  c.frames = static_cast<int>(sequence.frames.size());
  c.truth = result.world_T_camera_truth.has_value() &&
            result.world_T_camera_truth->size() == result.world_T_camera_odometry.size();
  c.refined = result.world_T_camera_refined.size() == result.world_T_camera_odometry.size() &&
              !result.world_T_camera_refined.empty();
  c.vertical = VerticalAxis(c.truth ? *result.world_T_camera_truth : result.world_T_camera_odometry);

  std::string name = fs::path(sequence.directory).filename().string();
  if (name.empty()) name = fs::path(sequence.directory).parent_path().filename().string();
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>junction-sfm: " +
                     Html(name) + "</title>\n<style>\n" + kStyle + "</style>\n</head>\n<body>\n";
  html += "<h1>junction-sfm report: " + Html(name) + "</h1>\n";
  html += "<p class=\"note\">Sequence <code>" + Html(sequence.directory) +
          "</code>. The other outputs of the run are in the directory of this page (docs/formats.md).</p>\n";
  html +=
      "<nav><a href=\"#summary\">summary</a><a href=\"#trajectories\">trajectories</a><a "
      "href=\"#errors\">errors</a>"
      "<a href=\"#junctions\">junctions</a><a href=\"#matches\">matches</a><a href=\"#match-images\">match "
      "pictures</a><a href=\"#wireframe\">wireframe</a><a href=\"#view3d-title\">3D</a></nav>\n";
  html += SummarySection(c);
  html += TrajectorySection(c);
  html += ErrorSection(c);
  html += JunctionSection(c);
  html += MatchSection(c);
  html += MatchPictureSection(c, images, stored_images_or_empty);
  html += WireframeSection(c);
  return html + "</body>\n</html>\n";
}

Status WriteReport(const Sequence& sequence, const PipelineResult& result,
                   const std::vector<cv::Mat>& undistorted_images_or_empty, const std::string& output_dir,
                   const std::vector<cv::Mat>& stored_images_or_empty) {
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory(output_dir));
  return WriteFileAtomically(
      (fs::path(output_dir) / "report.html").string(),
      ReportHtml(sequence, result, undistorted_images_or_empty, stored_images_or_empty));
}

}  // namespace sfm
