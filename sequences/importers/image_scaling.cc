#include "sequences/importers/image_scaling.h"

#include <algorithm>
#include <cmath>

namespace sfm {

Status ImageScaleOptions::Check() const {
  if (!(scale >= 0 && scale <= 1)) return Status::Error("image scale must be in (0, 1], or 0 to use max_width");
  if (max_width < 0) return Status::Error("max_width must be >= 0 pixels (0 keeps the size)");
  return Status::Ok();
}

cv::Size ScaledImageSize(int width, int height, const ImageScaleOptions& options) {
  double scale = options.scale;
  if (scale == 0) scale = options.max_width > 0 && width > options.max_width ? double(options.max_width) / width : 1;
  return cv::Size(std::max(1, static_cast<int>(std::lround(scale * width))),
                  std::max(1, static_cast<int>(std::lround(scale * height))));
}

Camera ScaleCamera(const Camera& camera, const cv::Size& size) {
  // The scales cv::resize itself uses: from the two sizes, not from the requested factor.
  const double sx = double(size.width) / camera.width, sy = double(size.height) / camera.height;
  Camera scaled = camera;
  scaled.width = size.width;
  scaled.height = size.height;
  scaled.fx = sx * camera.fx;
  scaled.fy = sy * camera.fy;
  scaled.cx = sx * (camera.cx + 0.5) - 0.5;
  scaled.cy = sy * (camera.cy + 0.5) - 0.5;
  return scaled;
}

}  // namespace sfm
