#include "sequences/generator/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <glog/logging.h>

#include "sequences/generator/random.h"

namespace sfm {
namespace {

// Sutherland-Hodgman clipping of a polygon (camera frame) against z >= near. The point where an
// edge crosses the plane is computed from its inside end-point, so that two faces sharing an edge
// get the very same clipped vertex.
int ClipNear(const Eigen::Vector3d* in, int count, double near, Eigen::Vector3d* out) {
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& p = in[i];
    const Eigen::Vector3d& q = in[(i + 1) % count];
    const bool p_in = p.z() >= near, q_in = q.z() >= near;
    if (p_in) out[n++] = p;
    if (p_in != q_in) {
      const Eigen::Vector3d& a = p_in ? p : q;  // inside
      const Eigen::Vector3d& b = p_in ? q : p;  // outside
      const double t = (near - a.z()) / (b.z() - a.z());
      Eigen::Vector3d x = a + t * (b - a);
      x.z() = near;
      out[n++] = x;
    }
  }
  return n;
}

// One row (or column, with `stride`) of a separable filter, borders replicated.
void FilterLine(const float* in, int count, std::ptrdiff_t stride, const std::vector<double>& kernel, float* out) {
  const int radius = static_cast<int>(kernel.size() / 2);
  for (int x = 0; x < count; ++x) {
    double v = 0;
    if (x >= radius && x + radius < count) {
      const float* p = in + (x - radius) * stride;
      for (size_t k = 0; k < kernel.size(); ++k) v += kernel[k] * p[k * stride];
    } else {
      for (int k = -radius; k <= radius; ++k) v += kernel[k + radius] * in[std::clamp(x + k, 0, count - 1) * stride];
    }
    out[x * stride] = static_cast<float>(v);
  }
}

// Separable Gaussian blur of a float image, borders replicated.
void GaussianBlur(int width, int height, double sigma, std::vector<float>* image) {
  if (sigma <= 0) return;
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> kernel(2 * radius + 1);
  double sum = 0;
  for (int k = -radius; k <= radius; ++k) sum += kernel[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (double& w : kernel) w /= sum;
  std::vector<float> tmp(image->size());
  for (int y = 0; y < height; ++y) {
    const size_t row = static_cast<size_t>(y) * width;
    FilterLine(image->data() + row, width, 1, kernel, tmp.data() + row);
  }
  for (int x = 0; x < width; ++x) FilterLine(tmp.data() + x, height, width, kernel, image->data() + x);
}

}  // namespace

Status RenderOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("render options: " + what); };
  if (supersampling < 1 || supersampling > 8) return error("supersampling must be in [1, 8]");
  if (!(blur_sigma >= 0 && blur_sigma <= 10)) return error("blur_sigma must be in [0, 10] px");
  if (!(noise_sigma >= 0 && noise_sigma <= 100)) return error("noise_sigma must be in [0, 100] grey levels");
  if (!(near > 0 && near < 1)) return error("near must be in (0, 1) m");
  if (!(background >= 0 && background <= 255)) return error("background must be in [0, 255]");
  return Status::Ok();
}

Renderer::Renderer(const Scene& scene, const Camera& camera, const RenderOptions& options)
    : scene_(scene), camera_(camera), options_(options) {
  const Status status = options.Check();
  CHECK(status.ok()) << status.message();
  CHECK_GT(camera.width, 0);
  CHECK_GT(camera.height, 0);
  shade_table_.resize(scene.faces.size() + 1);
  shade_table_[0] = static_cast<float>(options.background);
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    shade_table_[f + 1] = static_cast<float>(255.0 * scene.lighting.Shade(scene.faces[f]));
  }
  SetUpCanvasGeometry();
}

void Renderer::SetUpCanvasGeometry() {
  const int s = options_.supersampling, w = camera_.width, h = camera_.height;
  // Sample (i, j) of pixel (x, y) sits at x - 0.5 + (i + 0.5) / s.
  const double first = -0.5 + 0.5 / s;
  if (!camera_.HasDistortion()) {
    canvas_width_ = w * s;
    canvas_height_ = h * s;
    origin_x_ = origin_y_ = first;
    return;
  }
  // Undistorted position of every pixel corner of the stored image; the canvas is their bounding
  // box (the image border is enough for the usual, monotonic distortion, but the whole lattice is
  // needed anyway for the map below).
  const int lw = w + 1, lh = h + 1;
  std::vector<Eigen::Vector2d> lattice(static_cast<size_t>(lw) * lh);
  double min_x = -0.5, min_y = -0.5, max_x = w - 0.5, max_y = h - 0.5;
  for (int j = 0; j < lh; ++j) {
    for (int i = 0; i < lw; ++i) {
      const Eigen::Vector2d q = camera_.UndistortPixel({i - 0.5, j - 0.5});
      lattice[static_cast<size_t>(j) * lw + i] = q;
      min_x = std::min(min_x, q.x());
      max_x = std::max(max_x, q.x());
      min_y = std::min(min_y, q.y());
      max_y = std::max(max_y, q.y());
    }
  }
  // Strong distortion can send corners very far out; the canvas is capped at three image sizes.
  min_x = std::max(min_x, -1.0 * w);
  max_x = std::min(max_x, 2.0 * w);
  min_y = std::max(min_y, -1.0 * h);
  max_y = std::min(max_y, 2.0 * h);
  const double x0 = std::floor(min_x) - 1, y0 = std::floor(min_y) - 1;
  origin_x_ = x0 + first;
  origin_y_ = y0 + first;
  canvas_width_ = static_cast<int>(std::ceil(max_x) + 2 - x0) * s;
  canvas_height_ = static_cast<int>(std::ceil(max_y) + 2 - y0) * s;
  // Each output sample: bilinear between its pixel's four corners (the model is smooth, the error
  // is far below a sample), then the nearest canvas sample.
  sample_map_.assign(static_cast<size_t>(w) * s * h * s, -1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Eigen::Vector2d& c00 = lattice[static_cast<size_t>(y) * lw + x];
      const Eigen::Vector2d& c10 = lattice[static_cast<size_t>(y) * lw + x + 1];
      const Eigen::Vector2d& c01 = lattice[static_cast<size_t>(y + 1) * lw + x];
      const Eigen::Vector2d& c11 = lattice[static_cast<size_t>(y + 1) * lw + x + 1];
      for (int b = 0; b < s; ++b) {
        const double fy = (b + 0.5) / s;
        for (int a = 0; a < s; ++a) {
          const double fx = (a + 0.5) / s;
          const Eigen::Vector2d q =
              (1 - fy) * ((1 - fx) * c00 + fx * c10) + fy * ((1 - fx) * c01 + fx * c11);
          const long i = std::lround((q.x() - origin_x_) * s), j = std::lround((q.y() - origin_y_) * s);
          if (i < 0 || j < 0 || i >= canvas_width_ || j >= canvas_height_) continue;
          sample_map_[(static_cast<size_t>(y) * s + b) * w * s + static_cast<size_t>(x) * s + a] =
              static_cast<std::int32_t>(j * canvas_width_ + i);
        }
      }
    }
  }
}

void Renderer::Rasterise(const Pose3& world_T_camera, Canvas* canvas) const {
  CHECK(canvas != nullptr);
  const int s = options_.supersampling, cw = canvas_width_, ch = canvas_height_;
  canvas->width = cw;
  canvas->height = ch;
  canvas->scale = s;
  canvas->origin_x = origin_x_;
  canvas->origin_y = origin_y_;
  const size_t n = static_cast<size_t>(cw) * ch;
  canvas->face.assign(n, -1);
  canvas->inverse_depth.assign(n, 0.0f);

  const Pose3 camera_T_world = world_T_camera.Inverse();
  const Eigen::Matrix3d R = camera_T_world.RotationMatrix();
  const Eigen::Vector3d t = camera_T_world.translation;
  const double fx = camera_.fx, fy = camera_.fy, cx = camera_.cx, cy = camera_.cy;
  constexpr int kMaxVertices = 32;
  std::array<Eigen::Vector3d, kMaxVertices> in, clipped;
  std::array<Eigen::Vector2d, kMaxVertices> projected;

  for (int f = 0; f < static_cast<int>(scene_.faces.size()); ++f) {
    const Face& face = scene_.faces[f];
    const int count = static_cast<int>(face.vertices.size());
    CHECK_LT(count, kMaxVertices / 2);
    bool any_in_front = false;
    for (int i = 0; i < count; ++i) {
      in[i] = R * face.vertices[i] + t;
      any_in_front |= in[i].z() >= options_.near;
    }
    if (!any_in_front) continue;
    // The face's plane in the camera frame, n . X = d; 1/z is affine in the undistorted pixel.
    const Eigen::Vector3d nc = R * face.normal;
    const double d = nc.dot(in[0]);
    if (std::abs(d) < 1e-12) continue;  // seen exactly edge-on
    const int m = ClipNear(in.data(), count, options_.near, clipped.data());
    if (m < 3) continue;
    double min_y = 1e300, max_y = -1e300;
    for (int i = 0; i < m; ++i) {
      const double u = fx * clipped[i].x() / clipped[i].z() + cx;
      const double v = fy * clipped[i].y() / clipped[i].z() + cy;
      projected[i] = {(u - origin_x_) * s, (v - origin_y_) * s};
      min_y = std::min(min_y, projected[i].y());
      max_y = std::max(max_y, projected[i].y());
    }
    const int j0 = std::max(0, static_cast<int>(std::ceil(min_y)));
    const int j1 = std::min(ch - 1, static_cast<int>(std::floor(max_y)));
    if (j0 > j1) continue;
    // 1/z at sample (i, j) = A i + B j + C.
    const double A = nc.x() / (fx * s * d), B = nc.y() / (fy * s * d);
    const double C = (nc.x() * (origin_x_ - cx) / fx + nc.y() * (origin_y_ - cy) / fy + nc.z()) / d;
    for (int j = j0; j <= j1; ++j) {
      double left = 1e300, right = -1e300;
      for (int k = 0; k < m; ++k) {
        const Eigen::Vector2d* p = &projected[k];
        const Eigen::Vector2d* q = &projected[(k + 1) % m];
        if (p->y() == q->y()) continue;
        if (p->y() > q->y()) std::swap(p, q);  // the same arithmetic for a side shared by two faces
        if (j < p->y() || j > q->y()) continue;
        const double x = p->x() + (j - p->y()) * (q->x() - p->x()) / (q->y() - p->y());
        left = std::min(left, x);
        right = std::max(right, x);
      }
      if (left > right) continue;
      const int i0 = std::max(0, static_cast<int>(std::ceil(left)));
      const int i1 = std::min(cw - 1, static_cast<int>(std::floor(right)));
      const double row = B * j + C;
      float* depth = &canvas->inverse_depth[static_cast<size_t>(j) * cw];
      std::int32_t* ids = &canvas->face[static_cast<size_t>(j) * cw];
      for (int i = i0; i <= i1; ++i) {
        const float inverse_z = static_cast<float>(A * i + row);
        if (inverse_z > depth[i]) {
          depth[i] = inverse_z;
          ids[i] = f;
        }
      }
    }
  }
}

cv::Mat Renderer::Shade(const Canvas& canvas, std::uint64_t noise_seed) const {
  CHECK_EQ(canvas.width, canvas_width_);
  CHECK_EQ(canvas.height, canvas_height_);
  const int s = options_.supersampling, w = camera_.width, h = camera_.height;
  const float* table = shade_table_.data() + 1;  // table[-1] is the background
  const float inverse_count = 1.0f / static_cast<float>(s * s);
  std::vector<float> mean(static_cast<size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float sum = 0;
      if (sample_map_.empty()) {
        for (int b = 0; b < s; ++b) {
          const std::int32_t* ids = &canvas.face[(static_cast<size_t>(y) * s + b) * canvas_width_ + static_cast<size_t>(x) * s];
          for (int a = 0; a < s; ++a) sum += table[ids[a]];
        }
      } else {
        for (int b = 0; b < s; ++b) {
          const std::int32_t* map = &sample_map_[(static_cast<size_t>(y) * s + b) * w * s + static_cast<size_t>(x) * s];
          for (int a = 0; a < s; ++a) sum += map[a] < 0 ? table[-1] : table[canvas.face[map[a]]];
        }
      }
      mean[static_cast<size_t>(y) * w + x] = sum * inverse_count;
    }
  }
  GaussianBlur(w, h, options_.blur_sigma, &mean);
  cv::Mat image(h, w, CV_8UC1);
  Random random(noise_seed);
  for (int y = 0; y < h; ++y) {
    unsigned char* row = image.ptr<unsigned char>(y);
    for (int x = 0; x < w; ++x) {
      double v = mean[static_cast<size_t>(y) * w + x];
      if (options_.noise_sigma > 0) v += options_.noise_sigma * random.Gaussian();
      row[x] = static_cast<unsigned char>(std::clamp(std::floor(v + 0.5), 0.0, 255.0));
    }
  }
  return image;
}

cv::Mat Renderer::Render(const Pose3& world_T_camera, std::uint64_t noise_seed, Canvas* canvas) const {
  Canvas local;
  Canvas* target = canvas != nullptr ? canvas : &local;
  Rasterise(world_T_camera, target);
  return Shade(*target, noise_seed);
}

}  // namespace sfm
