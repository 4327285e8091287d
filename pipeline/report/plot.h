// A small plotting helper for report.html, drawn with OpenCV: axes with ticks at round numbers,
// tick labels, axis labels, title, legend, lines, markers, 2D segments and grouped bars, all
// anti-aliased. Enough for the report's figures, nothing more.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace sfm::plot {

// Tick positions at round numbers (step 1, 2 or 5 times a power of ten, and at least `min_step`)
// inside [lo, hi]: the smallest such step that gives at most `max_ticks` ticks. E.g. 0..7.3 with
// 6 ticks at most gives 0, 2, 4, 6. A range that is empty, of zero width or not finite gives none.
std::vector<double> NiceTicks(double lo, double hi, int max_ticks, double min_step = 0);

// The length of a map's scale bar for a visible range of `range` data units: the largest 1, 2 or 5
// times a power of ten not above a quarter of it (0 for a range that is not finite and positive).
double ScaleBarLength(double range);

// A tick value as text with just the decimals its step needs ("0.05", "2", "-1.5"; never "-0").
std::string TickLabel(double value, double step);

// BGR colours of the report's figures (colour-blind safe, after Okabe & Ito).
namespace colour {
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrey(150, 150, 150);
const cv::Scalar kOrange(0, 159, 230);
const cv::Scalar kBlue(178, 114, 0);
const cv::Scalar kGreen(115, 158, 0);
const cv::Scalar kVermillion(0, 94, 213);
const cv::Scalar kSky(233, 180, 86);
}  // namespace colour

class Plot {
 public:
  Plot(int width = 800, int height = 400);

  void SetTitle(const std::string& title) { title_ = title; }
  void SetXLabel(const std::string& label) { x_label_ = label; }
  void SetYLabel(const std::string& label) { y_label_ = label; }
  // One data unit is as long on x as on y (maps and side views); the shorter range is widened.
  void SetEqualAspect(bool equal) { equal_aspect_ = equal; }
  // Fixed data ranges instead of those of the data; anything outside is clipped.
  void SetXRange(double lo, double hi);
  void SetYRange(double lo, double hi);
  // The automatic y range reaches down (or up) to 0 (errors, counts).
  void SetYFromZero(bool from_zero) { y_from_zero_ = from_zero; }
  // Ticks on x only at whole numbers (frame indices).
  void SetIntegerX(bool integer) { integer_x_ = integer; }
  // A scale bar of ScaleBarLength(x range) labelled "<length> <unit>" in a lower corner of the plot
  // area (the one hiding less data); empty unit: none. For maps drawn with SetEqualAspect.
  void SetScaleBar(const std::string& unit) { scale_bar_unit_ = unit; }

  // A polyline through (x[i], y[i]); a non-finite point breaks it. `label` empty: not in the legend.
  void AddLine(const std::vector<double>& x, const std::vector<double>& y, const cv::Scalar& colour,
               const std::string& label, int thickness = 2);
  // Filled dots of `radius` pixels.
  void AddMarkers(const std::vector<double>& x, const std::vector<double>& y, const cv::Scalar& colour,
                  const std::string& label, int radius = 3);
  // Unconnected segments {x0, y0, x1, y1}.
  void AddSegments(const std::vector<std::array<double, 4>>& segments, const cv::Scalar& colour,
                   const std::string& label, int thickness = 1);
  // Bars of height values[i] at x = x0 + i; several bar series share each x side by side.
  void AddBars(const std::vector<double>& values, const cv::Scalar& colour, const std::string& label,
               double x0 = 0);

  // The figure, 8-bit BGR, width x height.
  cv::Mat Render() const;

 private:
  enum class Kind { kLine, kMarkers, kSegments, kBars };
  struct Series {
    Kind kind = Kind::kLine;
    std::vector<double> x, y;                    // lines, markers, bars (x of each bar)
    std::vector<std::array<double, 4>> segments;  // segments
    cv::Scalar colour;
    std::string label;
    int size = 1;  // thickness or radius
  };

  int width_, height_;
  std::string title_, x_label_, y_label_, scale_bar_unit_;
  bool equal_aspect_ = false, y_from_zero_ = false, integer_x_ = false;
  bool fixed_x_ = false, fixed_y_ = false;
  double x_lo_ = 0, x_hi_ = 1, y_lo_ = 0, y_hi_ = 1;
  std::vector<Series> series_;
};

}  // namespace sfm::plot
