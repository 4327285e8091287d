#include "pipeline/overlay/junction_overlay.h"

#include <algorithm>
#include <cstdio>

#include <glog/logging.h>
#include <opencv2/imgproc.hpp>

namespace sfm {
namespace {

constexpr int kShift = 4;  // fractional bits of the drawing coordinates
constexpr JunctionType kTypes[] = {JunctionType::kL, JunctionType::kY, JunctionType::kArrow,
                                   JunctionType::kT, JunctionType::kX, JunctionType::kN};

cv::Point Fixed(const Eigen::Vector2d& p, int scale) {
  const double f = 1 << kShift;
  return cv::Point(cvRound(((p.x() + 0.5) * scale - 0.5) * f), cvRound(((p.y() + 0.5) * scale - 0.5) * f));
}

}  // namespace

cv::Scalar JunctionTypeColour(JunctionType type) {
  switch (type) {
    case JunctionType::kL: return cv::Scalar(0, 0, 255);
    case JunctionType::kY: return cv::Scalar(0, 210, 0);
    case JunctionType::kArrow: return cv::Scalar(255, 60, 0);
    case JunctionType::kT: return cv::Scalar(255, 0, 255);
    case JunctionType::kX: return cv::Scalar(0, 255, 255);
    case JunctionType::kN: return cv::Scalar(255, 255, 255);
  }
  return cv::Scalar(128, 128, 128);
}

cv::Mat DrawJunctionOverlay(const cv::Mat& image, const LineSegments& segments, const Junctions& junctions,
                            int scale, const std::vector<OverlayMarks>& marks) {
  CHECK(!image.empty() && image.depth() == CV_8U && (image.channels() == 1 || image.channels() == 3));
  CHECK_GE(scale, 1);
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::Mat dimmed;
  grey.convertTo(dimmed, CV_8U, 0.7, 20);  // keep the colours readable on white walls
  cv::Mat canvas;
  cv::cvtColor(dimmed, canvas, cv::COLOR_GRAY2BGR);
  if (scale > 1) cv::resize(canvas, canvas, cv::Size(), scale, scale, cv::INTER_NEAREST);

  const cv::Scalar segment_colour(255, 255, 0);
  for (const OverlayMarks& m : marks) {
    for (const LineSegment& s : m.lines) {
      cv::line(canvas, Fixed(s.p0, scale), Fixed(s.p1, scale), m.colour, 1, cv::LINE_AA, kShift);
    }
  }
  for (const LineSegment& s : segments) {
    cv::line(canvas, Fixed(s.p0, scale), Fixed(s.p1, scale), segment_colour, 1, cv::LINE_AA, kShift);
  }
  int counts[6] = {0, 0, 0, 0, 0, 0};
  const int thickness = scale >= 3 ? 2 : 1;
  for (const Junction& j : junctions) {
    const cv::Scalar colour = JunctionTypeColour(j.type);
    for (const JunctionSegment& s : j.segments) {
      cv::line(canvas, Fixed(j.location, scale), Fixed(s.end, scale), colour, thickness, cv::LINE_AA, kShift);
    }
    ++counts[static_cast<int>(j.type)];
  }
  const int radius = std::max(2, scale + 1);
  for (const Junction& j : junctions) {
    const cv::Point at = Fixed(j.location, scale);
    cv::circle(canvas, at, (radius + 1) << kShift, cv::Scalar(0, 0, 0), cv::FILLED, cv::LINE_AA, kShift);
    cv::circle(canvas, at, radius << kShift, JunctionTypeColour(j.type), cv::FILLED, cv::LINE_AA, kShift);
  }
  for (const OverlayMarks& m : marks) {
    for (const Eigen::Vector2d& p : m.points) {
      cv::circle(canvas, Fixed(p, scale), (3 * radius) << kShift, m.colour, 1, cv::LINE_AA, kShift);
    }
  }

  // Legend, top left: one row per type (and per kind of mark) with its count.
  std::vector<std::pair<std::string, cv::Scalar>> rows;
  rows.emplace_back("segments " + std::to_string(segments.size()), segment_colour);
  for (JunctionType type : kTypes) {
    rows.emplace_back(std::string(JunctionTypeName(type)) + " " + std::to_string(counts[static_cast<int>(type)]),
                      JunctionTypeColour(type));
  }
  for (const OverlayMarks& m : marks) {
    rows.emplace_back(m.label + " " + std::to_string(m.points.empty() ? m.lines.size() : m.points.size()), m.colour);
  }
  const double font_scale = 0.4;
  const int row_height = 14, width = 150;
  cv::Mat box = canvas(cv::Rect(0, 0, std::min(width, canvas.cols), std::min(row_height * static_cast<int>(rows.size()) + 6, canvas.rows)));
  box *= 0.3;
  for (size_t i = 0; i < rows.size(); ++i) {
    const int y = 4 + row_height * static_cast<int>(i) + row_height / 2;
    cv::circle(canvas, cv::Point(10, y), 4, rows[i].second, cv::FILLED, cv::LINE_AA);
    cv::putText(canvas, rows[i].first, cv::Point(20, y + 4), cv::FONT_HERSHEY_SIMPLEX, font_scale,
                cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  return canvas;
}

}  // namespace sfm
