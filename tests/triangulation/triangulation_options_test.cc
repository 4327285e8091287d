#include "backend/triangulation/triangulation_options.h"

#include <gtest/gtest.h>

#include <limits>

namespace sfm {
namespace {

TEST(TriangulationOptionsTest, DefaultsPass) { EXPECT_TRUE(TriangulationOptions().Check().ok()); }

TEST(TriangulationOptionsTest, EachBadValueIsReported) {
  TriangulationOptions options;
  options.point.min_parallax_deg = 0;
  EXPECT_EQ(options.Check().message(), "PointTriangulationOptions: min_parallax_deg must be in (0, 90)");
  options = TriangulationOptions();
  options.point.max_reprojection_error_px = std::numeric_limits<double>::infinity();
  EXPECT_EQ(options.Check().message(),
            "PointTriangulationOptions: max_reprojection_error_px must be finite and > 0");
  options = TriangulationOptions();
  options.point.refinement_iterations = -1;
  EXPECT_EQ(options.Check().message(), "PointTriangulationOptions: refinement_iterations must be >= 0");
  options = TriangulationOptions();
  options.line.min_plane_angle_deg = 90;
  EXPECT_EQ(options.Check().message(), "LineTriangulationOptions: min_plane_angle_deg must be in (0, 90)");
  options = TriangulationOptions();
  options.line.min_centre_spread_deg = 0;
  EXPECT_EQ(options.Check().message(), "LineTriangulationOptions: min_centre_spread_deg must be in (0, 90)");
  options = TriangulationOptions();
  options.point.min_depth_m = -0.1;
  EXPECT_EQ(options.Check().message(), "PointTriangulationOptions: min_depth_m must be finite and >= 0");
  options = TriangulationOptions();
  options.line.min_depth_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(options.Check().message(), "LineTriangulationOptions: min_depth_m must be finite and >= 0");
  options = TriangulationOptions();
  options.line.max_reprojection_error_px = -1;
  EXPECT_EQ(options.Check().message(),
            "LineTriangulationOptions: max_reprojection_error_px must be finite and > 0");
}

}  // namespace
}  // namespace sfm
