#include "pipeline/report/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glog/logging.h>
#include <opencv2/imgproc.hpp>

namespace sfm::plot {
namespace {

constexpr int kShift = 4;  // fractional bits of drawing coordinates
constexpr double kFixed = 1 << kShift;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTickFont = 0.42, kLabelFont = 0.5, kTitleFont = 0.58;
const cv::Scalar kText(40, 40, 40), kGridColour(232, 232, 232), kFrameColour(90, 90, 90);

cv::Point Fixed(const cv::Point2d& p) { return cv::Point(cvRound(p.x * kFixed), cvRound(p.y * kFixed)); }

enum class Align { kLeft, kCentre, kRight };

// Text anchored at its left end, centre or right end; `at.y` is the vertical centre of the capitals.
void PutText(cv::Mat* canvas, const std::string& text, cv::Point at, Align align, double scale,
             const cv::Scalar& colour = kText, int thickness = 1) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, thickness, &baseline);
  int x = at.x;
  if (align == Align::kCentre) x -= size.width / 2;
  if (align == Align::kRight) x -= size.width;
  cv::putText(*canvas, text, cv::Point(x, at.y + size.height / 2), kFont, scale, colour, thickness, cv::LINE_AA);
}

int TextWidth(const std::string& text, double scale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline).width;
}

// Text turned 90 degrees counter-clockwise, centred on `centre` (a y-axis label).
void PutVerticalText(cv::Mat* canvas, const std::string& text, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &baseline);
  cv::Mat strip(size.height + baseline + 4, size.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(strip, text, cv::Point(2, size.height + 2), kFont, scale, kText, 1, cv::LINE_AA);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect where = cv::Rect(centre.x - turned.cols / 2, centre.y - turned.rows / 2, turned.cols, turned.rows) &
                         cv::Rect(0, 0, canvas->cols, canvas->rows);
  if (where.area() == 0) return;
  const cv::Rect from(where.x - (centre.x - turned.cols / 2), where.y - (centre.y - turned.rows / 2), where.width,
                      where.height);
  cv::Mat target = (*canvas)(where);
  cv::min(target, turned(from), target);  // dark text over the white margin
}

// Liang-Barsky: clips the segment a-b to the rectangle [x0, x1] x [y0, y1]; false when nothing is left.
bool ClipSegment(cv::Point2d* a, cv::Point2d* b, double x0, double y0, double x1, double y1) {
  double t0 = 0, t1 = 1;
  const double dx = b->x - a->x, dy = b->y - a->y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a->x - x0, x1 - a->x, a->y - y0, y1 - a->y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (t0 > t1) return false;
  const cv::Point2d start = *a;
  *a = start + t0 * cv::Point2d(dx, dy);
  *b = start + t1 * cv::Point2d(dx, dy);
  return true;
}

bool Finite(double x, double y) { return std::isfinite(x) && std::isfinite(y); }

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool Empty() const { return !(lo <= hi); }
};

// A range of zero width (one value) made wide enough to draw.
void Widen(Range* range) {
  if (range->Empty()) {
    range->lo = 0;
    range->hi = 1;
  } else if (range->hi - range->lo <= 1e-12 * std::max(1.0, std::abs(range->lo))) {
    const double half = range->lo == 0 ? 1.0 : 0.1 * std::abs(range->lo);
    range->lo -= half;
    range->hi += half;
  }
}

}  // namespace

std::vector<double> NiceTicks(double lo, double hi, int max_ticks, double min_step) {
  std::vector<double> ticks;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo) || max_ticks < 1) return ticks;
  const double span = hi - lo;
  double step = std::pow(10.0, std::floor(std::log10(span / max_ticks)));
  const double multipliers[] = {1, 2, 5};
  // Walk 1, 2, 5, 10, 20, ... times that power of ten until the ticks are few enough.
  for (int k = 0;; ++k) {
    const double candidate = step * multipliers[k % 3] * std::pow(10.0, k / 3);
    if (candidate < min_step) continue;
    const double first = std::ceil(lo / candidate - 1e-9), last = std::floor(hi / candidate + 1e-9);
    if (last - first + 1 <= max_ticks) {
      for (double i = first; i <= last; ++i) ticks.push_back(i * candidate);
      return ticks;
    }
  }
}

std::string TickLabel(double value, double step) {
  const int decimals = step > 0 ? std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9))) : 2;
  if (std::abs(value) < std::abs(step) * 1e-6) value = 0;  // no "-0"
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

Plot::Plot(int width, int height) : width_(width), height_(height) {
  CHECK_GE(width, 200);
  CHECK_GE(height, 150);
}

double ScaleBarLength(double range) {
  if (!(range > 0 && std::isfinite(range))) return 0;
  const double quarter = range / 4;
  const double power = std::pow(10.0, std::floor(std::log10(quarter)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * power <= quarter * (1 + 1e-12)) return m * power;
  }
  return power;
}

void Plot::SetXRange(double lo, double hi) {
  CHECK_LT(lo, hi);
  fixed_x_ = true;
  x_lo_ = lo;
  x_hi_ = hi;
}

void Plot::SetYRange(double lo, double hi) {
  CHECK_LT(lo, hi);
  fixed_y_ = true;
  y_lo_ = lo;
  y_hi_ = hi;
}

void Plot::AddLine(const std::vector<double>& x, const std::vector<double>& y, const cv::Scalar& colour,
                   const std::string& label, int thickness) {
  CHECK_EQ(x.size(), y.size());
  series_.push_back({Kind::kLine, x, y, {}, colour, label, thickness});
}

void Plot::AddMarkers(const std::vector<double>& x, const std::vector<double>& y, const cv::Scalar& colour,
                      const std::string& label, int radius) {
  CHECK_EQ(x.size(), y.size());
  series_.push_back({Kind::kMarkers, x, y, {}, colour, label, radius});
}

void Plot::AddSegments(const std::vector<std::array<double, 4>>& segments, const cv::Scalar& colour,
                       const std::string& label, int thickness) {
  series_.push_back({Kind::kSegments, {}, {}, segments, colour, label, thickness});
}

void Plot::AddBars(const std::vector<double>& values, const cv::Scalar& colour, const std::string& label, double x0) {
  Series bars{Kind::kBars, {}, values, {}, colour, label, 0};
  for (size_t i = 0; i < values.size(); ++i) bars.x.push_back(x0 + static_cast<double>(i));
  series_.push_back(std::move(bars));
}

cv::Mat Plot::Render() const {
  cv::Mat canvas(height_, width_, CV_8UC3, cv::Scalar(255, 255, 255));

  // Data ranges.
  Range xr, yr;
  bool has_bars = false;
  int bar_groups = 0;
  for (const Series& s : series_) {
    if (s.kind == Kind::kSegments) {
      for (const auto& g : s.segments) {
        if (!Finite(g[0], g[1]) || !Finite(g[2], g[3])) continue;
        xr.Add(g[0]), xr.Add(g[2]), yr.Add(g[1]), yr.Add(g[3]);
      }
      continue;
    }
    if (s.kind == Kind::kBars) {
      has_bars = true;
      ++bar_groups;
      for (size_t i = 0; i < s.x.size(); ++i) {
        if (!Finite(s.x[i], s.y[i])) continue;
        xr.Add(s.x[i] - 0.5), xr.Add(s.x[i] + 0.5), yr.Add(s.y[i]), yr.Add(0);
      }
      continue;
    }
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (Finite(s.x[i], s.y[i])) xr.Add(s.x[i]), yr.Add(s.y[i]);
    }
  }
  if (y_from_zero_ && !yr.Empty()) yr.Add(0);
  Widen(&xr);
  Widen(&yr);
  double x_lo = xr.lo, x_hi = xr.hi, y_lo = yr.lo, y_hi = yr.hi;
  if (!has_bars) {  // a little air around lines and dots; bars already span x +- 0.5
    const double pad = 0.04 * (x_hi - x_lo);
    x_lo -= pad, x_hi += pad;
  }
  {
    const double pad = 0.06 * (y_hi - y_lo);
    if (!(y_from_zero_ || has_bars) || y_lo < 0) y_lo -= pad;
    if (!(y_from_zero_ || has_bars) || y_hi > 0) y_hi += pad;
  }
  if (fixed_x_) x_lo = x_lo_, x_hi = x_hi_;
  if (fixed_y_) y_lo = y_lo_, y_hi = y_hi_;

  // Layout: the plot area inside margins for title, tick labels and axis labels.
  const int top = title_.empty() ? 14 : 36;
  const int bottom = x_label_.empty() ? 30 : 52;
  const int right = 18;
  // Left margin from the widest y tick label, found with a first guess of the area's height.
  const int area_h = height_ - top - bottom;
  int left = 0;
  std::vector<double> y_ticks;
  for (int pass = 0; pass < 2; ++pass) {
    const int area_w = width_ - (pass == 0 ? 70 : left) - right;
    if (equal_aspect_) {  // widen the shorter range so that a unit is as long on both axes
      const double units_per_px = std::max((x_hi - x_lo) / area_w, (y_hi - y_lo) / area_h);
      const double xc = 0.5 * (x_lo + x_hi), yc = 0.5 * (y_lo + y_hi);
      x_lo = xc - 0.5 * units_per_px * area_w, x_hi = xc + 0.5 * units_per_px * area_w;
      y_lo = yc - 0.5 * units_per_px * area_h, y_hi = yc + 0.5 * units_per_px * area_h;
    }
    y_ticks = NiceTicks(y_lo, y_hi, std::max(3, area_h / 50));
    const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
    int widest = 0;
    for (double t : y_ticks) widest = std::max(widest, TextWidth(TickLabel(t, y_step), kTickFont));
    left = widest + 14 + (y_label_.empty() ? 0 : 24);
  }
  const cv::Rect area(left, top, width_ - left - right, area_h);
  const std::vector<double> x_ticks =
      NiceTicks(x_lo, x_hi, std::max(3, area.width / 80), integer_x_ ? 1.0 : 0.0);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;

  // Data -> canvas pixels (double).
  auto to_px = [&](double x, double y) {
    return cv::Point2d(area.x + (x - x_lo) / (x_hi - x_lo) * (area.width - 1),
                       area.y + (y_hi - y) / (y_hi - y_lo) * (area.height - 1));
  };

  // Grid, then the data clipped to the area, then the frame, ticks and text over it.
  for (double t : x_ticks) {
    const int px = cvRound(to_px(t, 0).x);
    cv::line(canvas, cv::Point(px, area.y), cv::Point(px, area.br().y - 1), kGridColour, 1);
  }
  for (double t : y_ticks) {
    const int py = cvRound(to_px(0, t).y);
    cv::line(canvas, cv::Point(area.x, py), cv::Point(area.br().x - 1, py), kGridColour, 1);
  }

  cv::Mat plot_area = canvas(area);
  const cv::Point2d origin(area.x, area.y);
  auto draw_segment = [&](cv::Point2d a, cv::Point2d b, const cv::Scalar& colour, int thickness) {
    a -= origin, b -= origin;
    const double m = 4;  // clip a little outside so that thick line ends are drawn whole
    if (!ClipSegment(&a, &b, -m, -m, area.width - 1 + m, area.height - 1 + m)) return;
    cv::line(plot_area, Fixed(a), Fixed(b), colour, thickness, cv::LINE_AA, kShift);
  };
  std::vector<cv::Point2d> occupied;  // pixels covered by data, for placing the legend
  int bar_group = 0;
  for (const Series& s : series_) {
    switch (s.kind) {
      case Kind::kLine:
        for (size_t i = 0; i + 1 < s.x.size(); ++i) {
          if (!Finite(s.x[i], s.y[i]) || !Finite(s.x[i + 1], s.y[i + 1])) continue;
          const cv::Point2d a = to_px(s.x[i], s.y[i]), b = to_px(s.x[i + 1], s.y[i + 1]);
          draw_segment(a, b, s.colour, s.size);
          for (int k = 0; k <= 8; ++k) occupied.push_back(a + (b - a) * (k / 8.0));
        }
        if (s.x.size() == 1 && Finite(s.x[0], s.y[0])) {
          const cv::Point2d p = to_px(s.x[0], s.y[0]) - origin;
          cv::circle(plot_area, Fixed(p), (s.size + 1) << kShift, s.colour, cv::FILLED, cv::LINE_AA, kShift);
        }
        break;
      case Kind::kMarkers:
        for (size_t i = 0; i < s.x.size(); ++i) {
          if (!Finite(s.x[i], s.y[i])) continue;
          const cv::Point2d p = to_px(s.x[i], s.y[i]);
          occupied.push_back(p);
          cv::circle(plot_area, Fixed(p - origin), s.size << kShift, s.colour, cv::FILLED, cv::LINE_AA, kShift);
        }
        break;
      case Kind::kSegments:
        for (const auto& g : s.segments) {
          if (!Finite(g[0], g[1]) || !Finite(g[2], g[3])) continue;
          const cv::Point2d a = to_px(g[0], g[1]), b = to_px(g[2], g[3]);
          draw_segment(a, b, s.colour, s.size);
          for (int k = 0; k <= 4; ++k) occupied.push_back(a + (b - a) * (k / 4.0));
        }
        break;
      case Kind::kBars: {
        const double group_width = 0.8, bar_width = group_width / bar_groups;
        for (size_t i = 0; i < s.x.size(); ++i) {
          if (!Finite(s.x[i], s.y[i])) continue;
          const double x0 = s.x[i] - group_width / 2 + bar_group * bar_width;
          const cv::Point2d a = to_px(x0, s.y[i]), b = to_px(x0 + bar_width, 0);
          int l = cvRound(a.x), r = std::max(cvRound(b.x) - 1, l);
          const cv::Rect bar = cv::Rect(cv::Point(l, cvRound(std::min(a.y, b.y))),
                                        cv::Point(r + 1, cvRound(std::max(a.y, b.y)) + 1)) & area;
          if (bar.area() > 0) cv::rectangle(canvas, bar, s.colour, cv::FILLED);
          for (int k = 0; k <= 8; ++k) occupied.push_back(a + (cv::Point2d(a.x, b.y) - a) * (k / 8.0));
        }
        ++bar_group;
        break;
      }
    }
  }
  if (!equal_aspect_ && y_lo < 0 && y_hi > 0) {  // the zero line of a graph (not of a map) that crosses it
    const int py = cvRound(to_px(0, 0).y);
    cv::line(canvas, cv::Point(area.x, py), cv::Point(area.br().x - 1, py), colour::kGrey, 1);
  }

  cv::rectangle(canvas, area, kFrameColour, 1);
  for (double t : x_ticks) {
    const int px = cvRound(to_px(t, 0).x);
    cv::line(canvas, cv::Point(px, area.br().y), cv::Point(px, area.br().y + 4), kFrameColour, 1);
    PutText(&canvas, TickLabel(t, x_step), cv::Point(px, area.br().y + 14), Align::kCentre, kTickFont);
  }
  for (double t : y_ticks) {
    const int py = cvRound(to_px(0, t).y);
    cv::line(canvas, cv::Point(area.x - 5, py), cv::Point(area.x - 1, py), kFrameColour, 1);
    PutText(&canvas, TickLabel(t, y_step), cv::Point(area.x - 8, py), Align::kRight, kTickFont);
  }
  if (!x_label_.empty()) {
    PutText(&canvas, x_label_, cv::Point(area.x + area.width / 2, height_ - 14), Align::kCentre, kLabelFont);
  }
  if (!y_label_.empty()) PutVerticalText(&canvas, y_label_, cv::Point(12, area.y + area.height / 2), kLabelFont);
  if (!title_.empty()) {
    PutText(&canvas, title_, cv::Point(area.x + area.width / 2, 17), Align::kCentre, kTitleFont, kText, 1);
  }

  // Scale bar: in the lower corner hiding less data, on a white box; the legend then avoids it.
  const double bar_length = scale_bar_unit_.empty() ? 0 : ScaleBarLength(x_hi - x_lo);
  if (bar_length > 0) {
    const int bar_px = cvRound(bar_length / (x_hi - x_lo) * (area.width - 1));
    const std::string label = TickLabel(bar_length, bar_length) + " " + scale_bar_unit_;
    const cv::Size box(std::max(bar_px, TextWidth(label, kTickFont)) + 16, 34);
    const cv::Rect left(area.x + 8, area.br().y - box.height - 8, box.width, box.height);
    const cv::Rect right(area.br().x - box.width - 8, left.y, box.width, box.height);
    size_t hidden_left = 0, hidden_right = 0;
    for (const cv::Point2d& p : occupied) {
      hidden_left += left.contains(cv::Point(cvRound(p.x), cvRound(p.y)));
      hidden_right += right.contains(cv::Point(cvRound(p.x), cvRound(p.y)));
    }
    const cv::Rect at = hidden_right < hidden_left ? right : left;
    cv::rectangle(canvas, at, cv::Scalar(255, 255, 255), cv::FILLED);
    const int y = at.br().y - 9, x0 = at.x + 8;
    cv::line(canvas, cv::Point(x0, y), cv::Point(x0 + bar_px, y), kText, 3);
    cv::line(canvas, cv::Point(x0, y - 5), cv::Point(x0, y + 3), kText, 1);
    cv::line(canvas, cv::Point(x0 + bar_px, y - 5), cv::Point(x0 + bar_px, y + 3), kText, 1);
    PutText(&canvas, label, cv::Point(x0, y - 14), Align::kLeft, kTickFont);
    for (int px = at.x; px < at.br().x; px += 4) {
      for (int py = at.y; py < at.br().y; py += 4) occupied.emplace_back(px, py);
    }
  }

  // Legend: in the corner of the plot area that hides the least data.
  std::vector<const Series*> entries;
  int legend_text = 0;
  for (const Series& s : series_) {
    if (s.label.empty()) continue;
    entries.push_back(&s);
    legend_text = std::max(legend_text, TextWidth(s.label, kTickFont));
  }
  if (!entries.empty()) {
    const int row = 18, sample = 26;
    const cv::Size box(legend_text + sample + 24, static_cast<int>(entries.size()) * row + 8);
    const cv::Point corners[] = {
        {area.br().x - box.width - 8, area.y + 8}, {area.x + 8, area.y + 8},
        {area.br().x - box.width - 8, area.br().y - box.height - 8}, {area.x + 8, area.br().y - box.height - 8}};
    cv::Rect best;
    size_t fewest = std::numeric_limits<size_t>::max();
    for (const cv::Point& corner : corners) {
      const cv::Rect candidate(corner, box);
      size_t hidden = 0;
      for (const cv::Point2d& p : occupied) hidden += candidate.contains(cv::Point(cvRound(p.x), cvRound(p.y)));
      if (hidden < fewest) fewest = hidden, best = candidate;
    }
    cv::rectangle(canvas, best, cv::Scalar(255, 255, 255), cv::FILLED);
    cv::rectangle(canvas, best, cv::Scalar(200, 200, 200), 1);
    for (size_t i = 0; i < entries.size(); ++i) {
      const Series& s = *entries[i];
      const int y = best.y + 4 + row / 2 + static_cast<int>(i) * row;
      const cv::Point a(best.x + 8, y), b(best.x + 8 + sample, y);
      switch (s.kind) {
        case Kind::kLine:
        case Kind::kSegments:
          cv::line(canvas, a, b, s.colour, std::max(2, s.size), cv::LINE_AA);
          break;
        case Kind::kMarkers:
          cv::circle(canvas, (a + b) / 2, std::max(3, s.size), s.colour, cv::FILLED, cv::LINE_AA);
          break;
        case Kind::kBars:
          cv::rectangle(canvas, cv::Rect(a.x + 6, y - 6, sample - 12, 12), s.colour, cv::FILLED);
          break;
      }
      PutText(&canvas, s.label, cv::Point(b.x + 10, y), Align::kLeft, kTickFont);
    }
  }
  return canvas;
}

}  // namespace sfm::plot
