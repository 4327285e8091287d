// Renderer: grey images of a polyhedral scene as a camera sees them.
//
// The scene is rasterised with a z-buffer into a supersampled "canvas" of the undistorted image
// plane (pinhole K, polygons clipped against the near plane since the camera is inside the room).
// Each face has one brightness (Lighting::Shade). The stored image is made from the canvas: every
// output pixel averages scale x scale samples (anti-aliasing); with lens distortion each sample
// position of the distorted image is first mapped to the undistorted plane (Camera::UndistortPixel),
// so straight 3D edges come out curved exactly as OpenCV's model says. Then a Gaussian blur (the
// optics) and additive Gaussian noise (the sensor), rounded to 8 bits. Every step is plain C++
// (no SIMD-dispatched OpenCV filter), so the same inputs give the same bytes on any machine.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "util/status.h"
#include "sequences/generator/scene.h"

namespace sfm {

struct RenderOptions {
  int supersampling = 3;     // samples per pixel along each axis (anti-aliasing), 1..8
  double blur_sigma = 0.7;   // px, Gaussian blur after anti-aliasing; 0: none
  double noise_sigma = 2.0;  // grey levels, additive Gaussian noise; 0: none
  double near = 0.05;        // m, near clipping plane
  double background = 0;     // grey level where no face is seen (never, inside a closed room)

  Status Check() const;
};

// The z-buffer of one view: per sample of the undistorted image plane, the nearest face.
struct Canvas {
  int width = 0, height = 0;          // samples
  int scale = 1;                      // samples per pixel along each axis
  double origin_x = 0, origin_y = 0;  // undistorted pixel coordinates of sample (0, 0)
  std::vector<std::int32_t> face;     // nearest face at each sample (row-major), -1: none
  std::vector<float> inverse_depth;   // 1 / (camera z) of that face there, 1/m; 0: none

  // Undistorted pixel -> continuous sample coordinates (sample (i, j) is at (i, j)).
  Eigen::Vector2d ToSample(const Eigen::Vector2d& pixel) const {
    return {(pixel.x() - origin_x) * scale, (pixel.y() - origin_y) * scale};
  }
  // Face at integer sample (i, j), or -1 outside the canvas or where no face is.
  int FaceAt(int i, int j) const {
    if (i < 0 || j < 0 || i >= width || j >= height) return -1;
    return face[static_cast<size_t>(j) * width + i];
  }
};

class Renderer {
 public:
  // `scene` and `camera` must outlive the renderer. CHECKs that the options pass Check(). With
  // distortion, builds the map from output samples to canvas samples once (about 0.1 s at VGA).
  Renderer(const Scene& scene, const Camera& camera, const RenderOptions& options);

  // Rasterises the scene seen from `world_T_camera` into `canvas` (resized as needed). The canvas
  // covers every undistorted position that some pixel of the stored image sees.
  void Rasterise(const Pose3& world_T_camera, Canvas* canvas) const;

  // The stored 8-bit grey image (camera size) from a rasterised canvas; the noise comes from
  // `noise_seed` alone.
  cv::Mat Shade(const Canvas& canvas, std::uint64_t noise_seed) const;

  // Rasterise then Shade; the canvas is returned when `canvas` is not null.
  cv::Mat Render(const Pose3& world_T_camera, std::uint64_t noise_seed, Canvas* canvas = nullptr) const;

  const Camera& camera() const { return camera_; }
  const RenderOptions& options() const { return options_; }

 private:
  void SetUpCanvasGeometry();

  const Scene& scene_;
  const Camera camera_;
  const RenderOptions options_;
  int canvas_width_ = 0, canvas_height_ = 0;
  double origin_x_ = 0, origin_y_ = 0;
  std::vector<float> shade_table_;        // [0]: background, [f + 1]: grey level of face f
  std::vector<std::int32_t> sample_map_;  // distortion only: output sample -> canvas sample, -1: off canvas
};

}  // namespace sfm
