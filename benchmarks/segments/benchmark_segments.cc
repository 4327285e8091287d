// benchmark_segments: speed and quality of the line segment detectors (docs/segments.md).
//
//   build-seg/bin/benchmark_segments --output segments_benchmark.md [--images_dir <dir>]
//
// Run from the repository's top directory (the default --vgg_dir is relative to it). Single
// thread. Per image, the methods run in turns, --repetitions rounds; a method's time is the median
// of its runs. The tables give the median over images of those times and of their ratio to
// cv::Canny's time on the same image in the same run, then, on images with ground truth, the
// quality measures of segment_evaluation.h.
// Ground truth: <stem>.lines beside <stem>.<ext> (VGG), or, for a generated sequence's images/,
// ../truth/frames/<stem>.txt.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <glog/logging.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/edge_drawing.hpp>
#include <opencv2/ximgproc/fast_line_detector.hpp>

#include "frontend/junctions/junction_detector.h"
#include "frontend/segments/endpoint_fit.h"
#include "frontend/segments/segment_detector.h"
#include "benchmarks/evaluation/segment_evaluation.h"
#include "util/atomic_file.h"
#include "sfm_app/flags/detector_flags.h"

DEFINE_string(vgg_dir, "../shared/data/vgg-corridor",
              "Directory of VGG Corridor images with ground truth (<stem>.lines); skipped if absent.");
DEFINE_string(images_dir, "", "Optional further directory of images (for example a sequence's images/).");
DEFINE_int32(repetitions, 7, "Runs of each method per image, taken in turns; the median time is kept.");
DEFINE_string(output, "", "Also write the markdown report to this file.");
DEFINE_double(min_segment_length, sfm::SegmentDetectorOptions().min_length,
              "Our detectors: shortest segment kept, px (to measure another value beside the default).");
DEFINE_string(overlay_dir, "", "If set, write <method>_<image>.png overlays of the segments found there.");

namespace sfm {
namespace {

using Clock = std::chrono::steady_clock;

struct Method {
  std::string name;
  std::function<LineSegments(const cv::Mat&)> detect;  // empty result for cv::Canny
  bool timing_only = false;  // timed, not in the quality tables (cv::Canny; fast + junctions repeats fast)
};

LineSegments FromVec4f(const std::vector<cv::Vec4f>& lines) {
  LineSegments segments;
  for (const cv::Vec4f& l : lines) {
    LineSegment s;
    s.p0 = Eigen::Vector2d(l[0], l[1]);
    s.p1 = Eigen::Vector2d(l[2], l[3]);
    segments.push_back(s);
  }
  return segments;
}

std::vector<Method> Methods() {
  std::vector<Method> methods;
  methods.push_back({"cv::Canny(50,150)",
                     [](const cv::Mat& grey) {
                       cv::Mat edges;
                       cv::Canny(grey, edges, 50, 150);
                       return LineSegments();
                     },
                     /*timing_only=*/true});
  SegmentDetectorOptions reference;
  reference.method = SegmentMethod::kReference;
  reference.min_length = FLAGS_min_segment_length;
  methods.push_back({"ours: reference (Canny/Devernay + Hough)",
                     [reference](const cv::Mat& grey) { return DetectLineSegments(grey, reference); }});
  SegmentDetectorOptions fast;
  fast.method = SegmentMethod::kFast;
  fast.min_length = FLAGS_min_segment_length;
  methods.push_back(
      {"ours: fast (Sobel + chaining)", [fast](const cv::Mat& grey) { return DetectLineSegments(grey, fast); }});
  // The speed goal is for segments and junctions together, in the same run as cv::Canny.
  JunctionDetectorOptions junction_options;
  methods.push_back({"ours: fast segments + junctions",
                     [fast, junction_options](const cv::Mat& grey) {
                       LineSegments segments = DetectLineSegments(grey, fast);
                       const Junctions junctions = DetectJunctions(segments, junction_options);
                       // Keep the junctions' work observable so it cannot be optimised away.
                       if (junctions.size() > segments.size() * segments.size() + 1) segments.clear();
                       return segments;
                     },
                     /*timing_only=*/true});
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector();
  methods.push_back({"OpenCV LSD", [lsd](const cv::Mat& grey) {
                       std::vector<cv::Vec4f> lines;
                       lsd->detect(grey, lines);
                       return FromVec4f(lines);
                     }});
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  methods.push_back({"OpenCV FastLineDetector", [fld](const cv::Mat& grey) {
                       std::vector<cv::Vec4f> lines;
                       fld->detect(grey, lines);
                       return FromVec4f(lines);
                     }});
  const cv::Ptr<cv::ximgproc::EdgeDrawing> ed = cv::ximgproc::createEdgeDrawing();
  methods.push_back({"OpenCV EdgeDrawing (EDLines)", [ed](const cv::Mat& grey) {
                       std::vector<cv::Vec4f> lines;
                       ed->detectEdges(grey);
                       ed->detectLines(lines);
                       return FromVec4f(lines);
                     }});
  return methods;
}

struct Image {
  std::string name;
  cv::Mat grey;
  bool has_truth = false;
  LineSegments truth;
};

// The images of `dir` (sorted by name) with their ground truth where there is one.
Status LoadImages(const std::string& dir, std::vector<Image>* images) {
  namespace fs = std::filesystem;
  std::vector<fs::path> paths;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".pgm" || ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".bmp" ||
        ext == ".tif" || ext == ".tiff") {
      paths.push_back(entry.path());
    }
  }
  std::sort(paths.begin(), paths.end());
  if (paths.empty()) return Status::Error(dir + ": no images (.pgm .png .jpg .ppm .bmp .tif)");
  for (const fs::path& path : paths) {
    Image image;
    image.name = path.filename().string();
    image.grey = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    if (image.grey.empty()) return Status::Error(path.string() + ": cannot read the image");
    fs::path lines = path;
    lines.replace_extension(".lines");
    const fs::path frame = path.parent_path().parent_path() / "truth" / "frames" / (path.stem().string() + ".txt");
    if (fs::exists(lines)) {
      SFM_RETURN_IF_ERROR(ReadVggLines(lines.string(), &image.truth));
      image.has_truth = true;
    } else if (fs::exists(frame)) {
      SFM_RETURN_IF_ERROR(ReadGeneratorSegments(frame.string(), &image.truth));
      image.has_truth = true;
    }
    images->push_back(std::move(image));
  }
  return Status::Ok();
}

double Median(std::vector<double> values) { return Quantile(std::move(values), 0.5); }

void WriteOverlay(const std::string& dir, const std::string& method, const Image& image,
                  const LineSegments& segments) {
  cv::Mat canvas;
  cv::cvtColor(image.grey, canvas, cv::COLOR_GRAY2BGR);
  for (const LineSegment& s : image.truth) {
    cv::line(canvas, cv::Point2d(s.p0.x(), s.p0.y()), cv::Point2d(s.p1.x(), s.p1.y()), cv::Scalar(0, 200, 0), 1,
             cv::LINE_AA);
  }
  for (const LineSegment& s : segments) {
    cv::line(canvas, cv::Point2d(s.p0.x(), s.p0.y()), cv::Point2d(s.p1.x(), s.p1.y()), cv::Scalar(0, 0, 255), 1,
             cv::LINE_AA);
    cv::circle(canvas, cv::Point2d(s.p0.x(), s.p0.y()), 1, cv::Scalar(255, 128, 0), cv::FILLED);
  }
  std::string tag;
  for (const char c : method) tag += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  const std::string stem = image.name.substr(0, image.name.rfind('.'));
  cv::imwrite(dir + "/" + tag + "_" + stem + ".png", canvas);
}

// Timing of every method on every image of one set, and the quality on those with ground truth.
struct SetResult {
  std::vector<std::vector<double>> ms;     // [method][image]
  std::vector<std::vector<double>> count;  // [method][image] segments found
  std::vector<SegmentEvaluation> quality;  // [method], pooled over images with ground truth
  int num_with_truth = 0;
};

SetResult RunSet(const std::vector<Method>& methods, const std::vector<Image>& images) {
  const SegmentEvaluationOptions evaluation_options;
  SetResult result;
  result.ms.resize(methods.size());
  result.count.resize(methods.size());
  result.quality.resize(methods.size());
  for (const Image& image : images) {
    if (image.has_truth) ++result.num_with_truth;
    // Repetitions go round the methods, so that a load change on a shared machine hits all of them
    // alike and the ratios to cv::Canny stay meaningful.
    std::vector<std::vector<double>> times(methods.size());
    std::vector<LineSegments> segments(methods.size());
    for (int r = 0; r < FLAGS_repetitions; ++r) {
      for (size_t m = 0; m < methods.size(); ++m) {
        const Clock::time_point start = Clock::now();
        segments[m] = methods[m].detect(image.grey);
        times[m].push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
      }
    }
    for (size_t m = 0; m < methods.size(); ++m) {
      result.ms[m].push_back(Median(times[m]));
      result.count[m].push_back(static_cast<double>(segments[m].size()));
      if (methods[m].timing_only) continue;
      if (image.has_truth) result.quality[m].Add(EvaluateSegments(segments[m], image.truth, evaluation_options));
      if (!FLAGS_overlay_dir.empty()) WriteOverlay(FLAGS_overlay_dir, methods[m].name, image, segments[m]);
    }
  }
  return result;
}

std::string SpeedTable(const std::vector<Method>& methods, const SetResult& result) {
  std::ostringstream out;
  out << "| method | median ms/image | median ratio to cv::Canny | segments/image |\n"
      << "|---|---:|---:|---:|\n";
  for (size_t m = 0; m < methods.size(); ++m) {
    std::vector<double> ratios;
    for (size_t i = 0; i < result.ms[m].size(); ++i) ratios.push_back(result.ms[m][i] / result.ms[0][i]);
    char row[256];
    std::snprintf(row, sizeof(row), "| %s | %.2f | %.2f | %s |\n", methods[m].name.c_str(), Median(result.ms[m]),
                  Median(ratios), m == 0 ? "-" : std::to_string(static_cast<int>(Median(result.count[m]))).c_str());
    out << row;
  }
  return out.str();
}

std::string QualityTable(const std::vector<Method>& methods, const SetResult& result) {
  const SegmentEvaluationOptions o;
  std::ostringstream out;
  char head[512];
  std::snprintf(head, sizeof(head),
                "| method | GT (>= %.0f px) covered (>= %.0f%% within %.1f px, %.0f deg) | GT matched (one segment >= %.0f%%) "
                "| end-point error median / p90, px | line distance median, px |\n"
                "|---|---:|---:|---:|---:|\n",
                o.min_true_length, 100 * o.min_coverage, o.max_distance, o.max_angle_deg, 100 * o.min_match_overlap);
  out << head;
  for (size_t m = 0; m < methods.size(); ++m) {
    if (methods[m].timing_only) continue;
    const SegmentEvaluation& q = result.quality[m];
    char row[512];
    std::snprintf(row, sizeof(row), "| %s | %.1f%% (%d/%d) | %.1f%% | %.2f / %.2f | %.2f |\n", methods[m].name.c_str(),
                  100 * q.CoveredShare(), q.num_covered, q.num_true, 100 * q.MatchedShare(),
                  Quantile(q.endpoint_errors, 0.5), Quantile(q.endpoint_errors, 0.9), Quantile(q.line_distances, 0.5));
    out << row;
  }
  return out.str();
}

// "lambda / mu" of the ML fit of eq. (5) to the samples with |t| <= limit, or "-" when one side
// has none.
std::string FitText(const std::vector<double>& t, double limit) {
  std::vector<double> kept;
  for (const double v : t) {
    if (std::abs(v) <= limit) kept.push_back(v);
  }
  const bool both_sides = std::any_of(kept.begin(), kept.end(), [](double v) { return v > 0; }) &&
                          std::any_of(kept.begin(), kept.end(), [](double v) { return v < 0; });
  if (!both_sides) return "-";
  const EndpointModel model = FitEndpointModel(kept);
  char text[64];
  std::snprintf(text, sizeof(text), "%.3f / %.3f", model.lambda, model.mu);
  return text;
}

// The end-point offsets t of the matched segments (eq. 8: detected minus true, outward positive)
// and the maximum-likelihood end-point model (5) fitted to them: on all of them, and on those
// within 10 px (the rest are mostly a segment joined to, or cut from, a collinear neighbour).
std::string EndpointTable(const std::vector<Method>& methods, const SetResult& result) {
  std::ostringstream out;
  out << "| method | end-points | share t >= 0 | t median / p10 / p90, px | lambda / mu (all t), 1/px "
         "| lambda / mu (abs(t) <= 10 px), 1/px |\n"
      << "|---|---:|---:|---:|---:|---:|\n";
  for (size_t m = 0; m < methods.size(); ++m) {
    if (methods[m].timing_only) continue;
    const std::vector<double>& t = result.quality[m].endpoint_t;
    const double beyond = static_cast<double>(std::count_if(t.begin(), t.end(), [](double v) { return v >= 0; }));
    char row[512];
    std::snprintf(row, sizeof(row), "| %s | %zu | %.2f | %.2f / %.2f / %.2f | %s | %s |\n", methods[m].name.c_str(),
                  t.size(), t.empty() ? 0.0 : beyond / t.size(), Quantile(t, 0.5), Quantile(t, 0.1), Quantile(t, 0.9),
                  FitText(t, INFINITY).c_str(), FitText(t, 10).c_str());
    out << row;
  }
  return out.str();
}

std::string Report(const std::vector<Method>& methods, const std::string& title, const std::vector<Image>& images,
                   const SetResult& result) {
  std::ostringstream out;
  out << "### " << title << " (" << images.size() << " images, " << images.front().grey.cols << "x"
      << images.front().grey.rows << ", " << FLAGS_repetitions << " runs each, 1 thread)\n\n"
      << SpeedTable(methods, result) << "\n";
  if (result.num_with_truth > 0) {
    out << "Quality on the " << result.num_with_truth << " images with ground truth:\n\n"
        << QualityTable(methods, result) << "\nEnd-point offsets t and the fitted end-point model (5):\n\n"
        << EndpointTable(methods, result) << "\n";
  }
  return out.str();
}

}  // namespace
}  // namespace sfm

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "speed and quality of the line segment detectors.\n"
      "  benchmark_segments [--vgg_dir <dir>] [--images_dir <dir>] [--output report.md] [flags]");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  if (argc > 1) {
    std::fprintf(stderr, "benchmark_segments: unexpected argument '%s' (flags are --name=value)\n", argv[1]);
    return 2;
  }
  if (FLAGS_repetitions < 1) {
    std::fprintf(stderr, "benchmark_segments: --repetitions must be >= 1\n");
    return 2;
  }
  if (!FLAGS_overlay_dir.empty()) std::filesystem::create_directories(FLAGS_overlay_dir);
  cv::setNumThreads(1);

  std::vector<std::pair<std::string, std::string>> sets;  // (title, directory)
  if (std::filesystem::is_directory(FLAGS_vgg_dir)) {
    sets.emplace_back("VGG Corridor", FLAGS_vgg_dir);
  } else {
    std::fprintf(stderr, "benchmark_segments: %s not found; skipping VGG Corridor\n", FLAGS_vgg_dir.c_str());
  }
  if (!FLAGS_images_dir.empty()) sets.emplace_back(FLAGS_images_dir, FLAGS_images_dir);
  if (sets.empty()) {
    std::fprintf(stderr, "benchmark_segments: no images: give --vgg_dir or --images_dir\n");
    return 2;
  }

  const std::vector<sfm::Method> methods = sfm::Methods();
  std::string report = "## Line segment detectors\n\n";
  for (const auto& [title, dir] : sets) {
    std::vector<sfm::Image> images;
    const sfm::Status status = sfm::LoadImages(dir, &images);
    if (!status.ok()) {
      std::fprintf(stderr, "benchmark_segments: %s\n", status.message().c_str());
      return 1;
    }
    report += sfm::Report(methods, title, images, sfm::RunSet(methods, images));
  }
  std::fputs(report.c_str(), stdout);
  if (!FLAGS_output.empty()) {
    const sfm::Status status = sfm::WriteFileAtomically(FLAGS_output, report);
    if (!status.ok()) {
      std::fprintf(stderr, "benchmark_segments: %s\n", status.message().c_str());
      return 1;
    }
  }
  return 0;
}
