#include "pipeline/overlay/match_overlay.h"

#include <algorithm>
#include <string>

#include <glog/logging.h>
#include <opencv2/imgproc.hpp>

namespace sfm {
namespace {

constexpr int kShift = 4;  // fractional bits of the drawing coordinates

// Pixel p of an image enlarged `scale` times and shifted right by `offset_x` (output pixels).
cv::Point At(const Eigen::Vector2d& p, int scale, int offset_x) {
  const double f = 1 << kShift;
  return cv::Point(cvRound((((p.x() + 0.5) * scale - 0.5) + offset_x) * f), cvRound(((p.y() + 0.5) * scale - 0.5) * f));
}

// Bright colours that stay apart on a dimmed grey image (BGR).
const cv::Scalar kPalette[] = {cv::Scalar(0, 0, 255),   cv::Scalar(0, 220, 0),   cv::Scalar(255, 80, 0),
                               cv::Scalar(0, 230, 255), cv::Scalar(255, 0, 255), cv::Scalar(255, 255, 0),
                               cv::Scalar(0, 140, 255), cv::Scalar(180, 105, 255)};
constexpr int kNumColours = sizeof(kPalette) / sizeof(kPalette[0]);

cv::Mat DimmedBgr(const cv::Mat& image, int scale) {
  CHECK(!image.empty() && image.depth() == CV_8U && (image.channels() == 1 || image.channels() == 3));
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::Mat dimmed, bgr;
  grey.convertTo(dimmed, CV_8U, 0.6, 25);
  cv::cvtColor(dimmed, bgr, cv::COLOR_GRAY2BGR);
  if (scale > 1) cv::resize(bgr, bgr, cv::Size(), scale, scale, cv::INTER_NEAREST);
  return bgr;
}

void DrawLabel(cv::Mat* canvas, const std::string& text, cv::Point at_fixed, bool wrong) {
  const double font = 0.4;
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, font, 1, &baseline);
  cv::Point at(at_fixed.x >> kShift, at_fixed.y >> kShift);
  at += cv::Point(4, -4);
  at.x = std::clamp(at.x, 0, std::max(0, canvas->cols - size.width - 1));
  at.y = std::clamp(at.y, size.height + 1, std::max(size.height + 1, canvas->rows - 2));
  const cv::Rect box(at.x - 1, at.y - size.height - 1, size.width + 2, size.height + 3);
  cv::rectangle(*canvas, box & cv::Rect(0, 0, canvas->cols, canvas->rows),
                wrong ? cv::Scalar(255, 255, 255) : cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(*canvas, text, at, cv::FONT_HERSHEY_SIMPLEX, font, wrong ? cv::Scalar(0, 0, 255) : cv::Scalar(255, 255, 255),
              1, cv::LINE_AA);
}

}  // namespace

cv::Mat DrawMatchOverlay(const cv::Mat& image_a, const Junctions& a, const cv::Mat& image_b, const Junctions& b,
                         const std::vector<JunctionMatch>& matches, int scale, const std::vector<bool>& correct) {
  CHECK_GE(scale, 1);
  CHECK(correct.empty() || correct.size() == matches.size());
  const cv::Mat left = DimmedBgr(image_a, scale), right = DimmedBgr(image_b, scale);
  const int gap = 8;
  cv::Mat canvas(std::max(left.rows, right.rows), left.cols + gap + right.cols, CV_8UC3, cv::Scalar(255, 255, 255));
  left.copyTo(canvas(cv::Rect(0, 0, left.cols, left.rows)));
  right.copyTo(canvas(cv::Rect(left.cols + gap, 0, right.cols, right.rows)));
  const int offset_b = left.cols + gap;
  const int thickness = scale >= 2 ? 2 : 1;

  std::vector<bool> matched_a(a.size(), false), matched_b(b.size(), false);
  for (const JunctionMatch& m : matches) {
    matched_a.at(m.index_a) = true;
    matched_b.at(m.index_b) = true;
  }
  const cv::Scalar grey(150, 150, 150);
  auto draw_unmatched = [&](const Junctions& junctions, const std::vector<bool>& matched, int offset) {
    for (size_t j = 0; j < junctions.size(); ++j) {
      if (matched[j]) continue;
      for (const JunctionSegment& s : junctions[j].segments) {
        cv::line(canvas, At(junctions[j].location, scale, offset), At(s.end, scale, offset), grey, 1, cv::LINE_AA, kShift);
      }
    }
  };
  draw_unmatched(a, matched_a, 0);
  draw_unmatched(b, matched_b, offset_b);

  for (size_t k = 0; k < matches.size(); ++k) {
    const JunctionMatch& m = matches[k];
    const Junction& ja = a[m.index_a];
    const Junction& jb = b[m.index_b];
    const int n_a = ja.NumSegments();
    const int n_b = jb.NumSegments();
    // A partial match's left-out segment (missing_a or missing_b) has no partner: drawn like an
    // unmatched junction's segments, thin and grey.
    if (m.missing_a >= 0) {
      cv::line(canvas, At(ja.location, scale, 0), At(ja.segments.at(m.missing_a).end, scale, 0), grey, 1,
               cv::LINE_AA, kShift);
    }
    if (m.missing_b >= 0) {
      cv::line(canvas, At(jb.location, scale, offset_b), At(jb.segments.at(m.missing_b).end, scale, offset_b),
               grey, 1, cv::LINE_AA, kShift);
    }
    for (int i = 0; i < n_a; ++i) {
      const int j = PartnerSegment(m, i, n_a, n_b);
      if (j < 0) continue;
      const cv::Scalar colour = kPalette[(i + 3 * static_cast<int>(k)) % kNumColours];
      cv::line(canvas, At(ja.location, scale, 0), At(ja.segments[i].end, scale, 0), colour, thickness, cv::LINE_AA, kShift);
      cv::line(canvas, At(jb.location, scale, offset_b), At(jb.segments[j].end, scale, offset_b), colour, thickness,
               cv::LINE_AA, kShift);
    }
  }
  // Dots and numbers last, so that no segment covers them.
  for (size_t k = 0; k < matches.size(); ++k) {
    const JunctionMatch& m = matches[k];
    const bool wrong = !correct.empty() && !correct[k];
    const std::string label = std::to_string(k + 1);
    for (const auto& [location, offset] : {std::pair{a[m.index_a].location, 0}, std::pair{b[m.index_b].location, offset_b}}) {
      const cv::Point at = At(location, scale, offset);
      cv::circle(canvas, at, 3 << kShift, cv::Scalar(0, 0, 0), cv::FILLED, cv::LINE_AA, kShift);
      cv::circle(canvas, at, 2 << kShift, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA, kShift);
      DrawLabel(&canvas, label, at, wrong);
    }
  }
  return canvas;
}

}  // namespace sfm
