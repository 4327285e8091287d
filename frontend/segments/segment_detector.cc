#include "frontend/segments/segment_detector.h"

#include <algorithm>

#include <cmath>
#include <sstream>

#include <glog/logging.h>

#include "frontend/segments/fast_segments.h"
#include "frontend/segments/hough_segments.h"
#include "frontend/segments/subpixel_edges.h"

namespace sfm {
namespace {

// "options.<name> = <value>: must be <rule>" when `ok` is false.
Status Require(bool ok, const char* name, double value, const char* rule) {
  if (ok) return Status::Ok();
  std::ostringstream message;
  message << "SegmentDetectorOptions." << name << " = " << value << ": must be " << rule;
  return Status::Error(message.str());
}

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

const char* ToString(SegmentMethod method) { return method == SegmentMethod::kFast ? "fast" : "reference"; }

Status FromString(const std::string& name, SegmentMethod* method) {
  for (const SegmentMethod m : {SegmentMethod::kFast, SegmentMethod::kReference}) {
    if (name == ToString(m)) {
      *method = m;
      return Status::Ok();
    }
  }
  return Status::Error("'" + name + "' is not a segment method ('fast' or 'reference')");
}

Status SegmentDetectorOptions::Check() const {
  SFM_RETURN_IF_ERROR(Require(Finite(edge_contrast_low) && edge_contrast_low > 0, "edge_contrast_low",
                              edge_contrast_low, "> 0"));
  SFM_RETURN_IF_ERROR(Require(Finite(edge_contrast_high) && edge_contrast_high >= edge_contrast_low,
                              "edge_contrast_high", edge_contrast_high, ">= edge_contrast_low"));
  SFM_RETURN_IF_ERROR(Require(Finite(min_length) && min_length >= 2, "min_length", min_length, ">= 2 pixels"));
  // Edge points of a diagonal edge are sqrt(2) apart: a smaller gap would split every such line.
  SFM_RETURN_IF_ERROR(Require(Finite(max_gap) && max_gap >= 1.5, "max_gap", max_gap, ">= 1.5 pixels"));
  SFM_RETURN_IF_ERROR(Require(Finite(border_margin) && border_margin >= 0, "border_margin", border_margin,
                              ">= 0 pixels"));
  const ReferenceSegmentOptions& r = reference;
  SFM_RETURN_IF_ERROR(Require(Finite(r.edge_sigma) && r.edge_sigma >= 0.5 && r.edge_sigma <= 10,
                              "reference.edge_sigma", r.edge_sigma, "in [0.5, 10] pixels"));
  SFM_RETURN_IF_ERROR(Require(Finite(r.hough_angle_step_deg) && r.hough_angle_step_deg >= 0.05 &&
                                  r.hough_angle_step_deg <= 10,
                              "reference.hough_angle_step_deg", r.hough_angle_step_deg, "in [0.05, 10] degrees"));
  SFM_RETURN_IF_ERROR(Require(Finite(r.hough_rho_step) && r.hough_rho_step >= 0.1 && r.hough_rho_step <= 10,
                              "reference.hough_rho_step", r.hough_rho_step, "in [0.1, 10] pixels"));
  SFM_RETURN_IF_ERROR(Require(Finite(r.vote_window_deg) && r.vote_window_deg >= 0 && r.vote_window_deg <= 90,
                              "reference.vote_window_deg", r.vote_window_deg, "in [0, 90] degrees"));
  SFM_RETURN_IF_ERROR(Require(r.min_votes >= 2, "reference.min_votes", r.min_votes, ">= 2"));
  SFM_RETURN_IF_ERROR(Require(Finite(r.fit_distance) && r.fit_distance > 0, "reference.fit_distance",
                              r.fit_distance, "> 0 pixels"));
  SFM_RETURN_IF_ERROR(Require(Finite(r.gather_distance) && r.gather_distance >= r.fit_distance,
                              "reference.gather_distance", r.gather_distance, ">= reference.fit_distance"));
  SFM_RETURN_IF_ERROR(Require(Finite(r.angle_tolerance_deg) && r.angle_tolerance_deg > 0 &&
                                  r.angle_tolerance_deg < 90,
                              "reference.angle_tolerance_deg", r.angle_tolerance_deg, "in (0, 90) degrees"));
  const FastSegmentOptions& f = fast;
  SFM_RETURN_IF_ERROR(Require(Finite(f.presmooth_sigma) && f.presmooth_sigma >= 0 && f.presmooth_sigma <= 5,
                              "fast.presmooth_sigma", f.presmooth_sigma, "in [0, 5] pixels"));
  SFM_RETURN_IF_ERROR(Require(Finite(f.line_tolerance) && f.line_tolerance > 0, "fast.line_tolerance",
                              f.line_tolerance, "> 0 pixels"));
  SFM_RETURN_IF_ERROR(Require(Finite(f.log10_nfa_max), "fast.log10_nfa_max", f.log10_nfa_max, "finite"));
  return Status::Ok();
}

LineSegments DetectLineSegments(const cv::Mat& grey, const SegmentDetectorOptions& options) {
  CHECK_EQ(grey.type(), CV_8UC1) << "DetectLineSegments needs an 8-bit single-channel image";
  const Status status = options.Check();
  CHECK(status.ok()) << status.message();
  LineSegments segments;
  if (options.method == SegmentMethod::kFast) {
    segments = DetectFastSegments(grey, options);
  } else {
    const double sigma = options.reference.edge_sigma;
    const std::vector<EdgePoint> edges =
        DetectSubpixelEdges(grey, sigma, StepGradient(options.edge_contrast_low, sigma),
                            StepGradient(options.edge_contrast_high, sigma));
    segments = HoughSegments(edges, grey.size(), options);
  }
  DropBorderSegments(grey.size(), options.border_margin, &segments);
  return segments;
}

void DropBorderSegments(const cv::Size& size, double margin, LineSegments* segments) {
  if (margin <= 0) return;
  const double right = size.width - 1 - margin, bottom = size.height - 1 - margin;
  const auto along_border = [&](const LineSegment& s) {
    return (s.p0.x() <= margin && s.p1.x() <= margin) || (s.p0.x() >= right && s.p1.x() >= right) ||
           (s.p0.y() <= margin && s.p1.y() <= margin) || (s.p0.y() >= bottom && s.p1.y() >= bottom);
  };
  segments->erase(std::remove_if(segments->begin(), segments->end(), along_border), segments->end());
}

}  // namespace sfm
