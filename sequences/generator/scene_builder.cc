#include "sequences/generator/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glog/logging.h>

#include "sequences/generator/random.h"

namespace sfm {
namespace {

// Furniture dimensions (m), from common office furniture.
constexpr double kWallGap = 0.02;          // furniture stands this far from its wall
constexpr double kBoardThickness = 0.025;  // shelf boards and side panels
constexpr double kCapOverhang = 0.01;      // a shelf's top board overhangs the sides by this
constexpr double kBoardRecess = 0.01;      // shelf boards are set back from the front by this
constexpr double kFlatOffset = 0.005;      // posters and door leaves stand this far off their wall
constexpr double kDoorWidth = 0.9, kDoorHeight = 2.05;
constexpr double kJambWidth = 0.07, kJambDepth = 0.03, kLintelDepth = 0.04;
constexpr double kSparseGapMin = 2.0, kSparseGapMax = 4.0;  // m of bare wall between two pieces (sparse)

// A wall seen from inside: s runs along it from `start`, d into the room, z up.
struct Wall {
  Eigen::Vector2d start, direction, inward;
  double length = 0;

  Eigen::Vector2d XY(double s, double d) const { return start + s * direction + d * inward; }
  Eigen::Vector3d At(double s, double d, double z) const {
    const Eigen::Vector2d xy = XY(s, d);
    return {xy.x(), xy.y(), z};
  }
  double Yaw() const { return std::atan2(direction.y(), direction.x()); }
  Eigen::Vector3d Inward3() const { return {inward.x(), inward.y(), 0}; }
  Eigen::Vector3d Along3() const { return {direction.x(), direction.y(), 0}; }
};

enum class Furniture { kCabinet, kShelf, kBoxStack, kTable, kDoor, kPoster };

class Builder {
 public:
  Builder(const SceneOptions& options, std::uint64_t seed, Scene* scene)
      : options_(options), random_(seed), scene_(scene) {
    scene_->lighting = options.lighting;
  }

  void BuildCorridor();
  void BuildRoom();

 private:
  double LightTerm(const Eigen::Vector3d& n) const {
    return options_.lighting.ambient + options_.lighting.diffuse * std::abs(n.dot(options_.lighting.direction));
  }
  double Shade(const Eigen::Vector3d& n, double albedo) const { return options_.lighting.Shade(n, albedo); }

  // An albedo in [low, high) such that faces of the given normals differ in shade by at least
  // min_contrast from each other and, as far as possible, from every shade in `avoid` (the floor,
  // the walls and what the object stands on). 200 random tries: the first that meets both, else
  // the one with the best background contrast among those whose own faces differ enough.
  double PickAlbedo(double low, double high, const std::vector<Eigen::Vector3d>& normals,
                    const std::vector<double>& avoid);
  // A yaw in base + [low, high) for which the side and top faces of a box differ in light term by at
  // least min_contrast / 0.4, so that any albedo above 0.4 keeps the box's own edges visible.
  double PickYaw(double base, double low, double high);
  // Shades an object is seen against: the floor and the wall it stands at (every wall for an
  // object in the middle of the room).
  std::vector<double> Background(const Wall* wall) const {
    if (wall == nullptr) return shell_shades_;
    return {shell_shades_[0], Shade(wall->Inward3(), wall_albedo_)};
  }
  std::vector<double> BoxShades(double yaw, double albedo) const;

  void BuildShell(const Eigen::Vector2d& floor_min, const Eigen::Vector2d& floor_max);
  void AddCeilingLight(const Eigen::Vector2d& centre, const Eigen::Vector2d& size);
  void FillWall(const Wall& wall, double s_begin, double s_end, bool allow_doors);
  double WidthOf(Furniture kind);
  // Each returns the top of what it built (m), for a poster above it.
  double AddCabinet(const Wall& wall, double s0, double width);
  double AddShelf(const Wall& wall, double s0, double width);
  double AddBoxStack(const Wall& wall, double s0, double width);
  double AddTable(const Wall& wall, double s0, double width);
  void AddDoor(const Wall& wall, double s0);
  void AddPoster(const Wall& wall, double s0, double width, double z0, double z1);
  // Boxes of decreasing size stacked on a base whose top is at `z` with footprint centre, yaw and
  // size. Returns the top of the stack.
  double StackBoxes(int object, const Eigen::Vector2d& centre, double yaw, double z, const Eigen::Vector2d& base_size,
                  double base_albedo, int count, double max_top, const std::vector<double>& background);
  void AddIsland(const Eigen::Vector2d& centre);

  const SceneOptions& options_;
  Random random_;
  Scene* scene_;
  double wall_albedo_ = 0.8;
  std::vector<double> shell_shades_;
};

double Builder::PickAlbedo(double low, double high, const std::vector<Eigen::Vector3d>& normals,
                           const std::vector<double>& avoid) {
  // Own faces: a hard constraint (they share wireframe edges). The background: as good as we can.
  double best = high, best_own = -1, best_background = -1;
  for (int attempt = 0; attempt < 200; ++attempt) {
    const double albedo = random_.Uniform(low, high);
    double own = std::numeric_limits<double>::infinity(), background = own;
    for (size_t i = 0; i < normals.size(); ++i) {
      const double shade_i = Shade(normals[i], albedo);
      for (double shade : avoid) background = std::min(background, std::abs(shade_i - shade));
      for (size_t j = i + 1; j < normals.size(); ++j) {
        own = std::min(own, std::abs(shade_i - Shade(normals[j], albedo)));
      }
    }
    const bool own_ok = own >= options_.min_contrast;
    if (own_ok && background >= options_.min_contrast) return albedo;
    const bool better = own_ok ? (best_own < options_.min_contrast || background > best_background)
                               : (best_own < options_.min_contrast && own > best_own);
    if (better) {
      best = albedo;
      best_own = own;
      best_background = background;
    }
  }
  return best;
}

double Builder::PickYaw(double base, double low, double high) {
  double yaw = base;
  for (int attempt = 0; attempt < 200; ++attempt) {
    yaw = base + random_.Uniform(low, high);
    const Eigen::Vector3d a(std::cos(yaw), std::sin(yaw), 0), b(-std::sin(yaw), std::cos(yaw), 0);
    const double la = LightTerm(a), lb = LightTerm(b), lz = LightTerm(Eigen::Vector3d::UnitZ());
    const double step = options_.min_contrast / 0.4;
    if (std::abs(la - lb) >= step && std::abs(la - lz) >= step && std::abs(lb - lz) >= step) return yaw;
  }
  return yaw;
}

std::vector<double> Builder::BoxShades(double yaw, double albedo) const {
  return {Shade({std::cos(yaw), std::sin(yaw), 0}, albedo), Shade({-std::sin(yaw), std::cos(yaw), 0}, albedo),
          Shade(Eigen::Vector3d::UnitZ(), albedo)};
}

void Builder::BuildShell(const Eigen::Vector2d& floor_min, const Eigen::Vector2d& floor_max) {
  const double h = options_.ceiling_height;
  scene_->floor_min = floor_min;
  scene_->floor_max = floor_max;
  scene_->ceiling_height = h;
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ(), ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY();
  // Floor darker than the walls, ceiling brightest; redrawn until every pair that meets differs.
  double floor_albedo = 0.4, ceiling_albedo = 0.9;
  for (int attempt = 0; attempt < 200; ++attempt) {
    floor_albedo = random_.Uniform(0.3, 0.5);
    wall_albedo_ = random_.Uniform(0.65, 0.85);
    ceiling_albedo = random_.Uniform(0.8, 0.95);
    const double floor_shade = Shade(up, floor_albedo), ceiling_shade = Shade(up, ceiling_albedo);
    const double wall_x = Shade(ex, wall_albedo_), wall_y = Shade(ey, wall_albedo_);
    // The shell's edges are the longest in the image: make them stand out well.
    const double c = 2.5 * options_.min_contrast;
    if (std::abs(floor_shade - wall_x) >= c && std::abs(floor_shade - wall_y) >= c &&
        std::abs(ceiling_shade - wall_x) >= c && std::abs(ceiling_shade - wall_y) >= c &&
        std::abs(wall_x - wall_y) >= c) {
      break;
    }
  }
  // What furniture is seen against: the floor and the walls (the ceiling only meets the walls).
  shell_shades_ = {Shade(up, floor_albedo), Shade(ex, wall_albedo_), Shade(ey, wall_albedo_)};
  const double x0 = floor_min.x(), y0 = floor_min.y(), x1 = floor_max.x(), y1 = floor_max.y();
  const Eigen::Vector3d b[4] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
  const Eigen::Vector3d t[4] = {{x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
  const Eigen::Vector3d centre(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * h);
  scene_->AddPolygon(scene_->AddObject("floor"), {b[0], b[1], b[2], b[3]}, floor_albedo, up);
  scene_->AddPolygon(scene_->AddObject("ceiling"), {t[0], t[1], t[2], t[3]}, ceiling_albedo, -up);
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    const Eigen::Vector3d facing = centre - 0.5 * (b[i] + t[j]);
    scene_->AddPolygon(scene_->AddObject("wall"), {b[i], b[j], t[j], t[i]}, wall_albedo_, facing);
  }
}

void Builder::AddCeilingLight(const Eigen::Vector2d& c, const Eigen::Vector2d& size) {
  const double z = options_.ceiling_height - kFlatOffset;
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y();
  scene_->AddPolygon(scene_->AddObject("ceiling_light"),
                     {{c.x() - hx, c.y() - hy, z}, {c.x() + hx, c.y() - hy, z}, {c.x() + hx, c.y() + hy, z},
                      {c.x() - hx, c.y() + hy, z}},
                     /*albedo=*/0.0, -Eigen::Vector3d::UnitZ(), /*emission=*/0.97);
}

double Builder::WidthOf(Furniture kind) {
  switch (kind) {
    case Furniture::kCabinet: return random_.Uniform(0.5, 1.2);
    case Furniture::kShelf: return random_.Uniform(0.6, 1.0);
    case Furniture::kBoxStack: return random_.Uniform(0.35, 0.7);
    case Furniture::kTable: return random_.Uniform(0.8, 1.4);
    case Furniture::kDoor: return kDoorWidth + 2 * kJambWidth;
    case Furniture::kPoster: return random_.Uniform(0.4, 1.0);
  }
  return 0.5;
}

void Builder::FillWall(const Wall& wall, double s_begin, double s_end, bool allow_doors) {
  // Relative frequencies of cabinet, shelf, box stack, table, door, poster. A sparse scene has
  // cabinets and doors only: plain boxes and frames, no small objects on or above them.
  static constexpr double kFullWeights[6] = {0.2, 0.2, 0.2, 0.12, 0.13, 0.15};
  static constexpr double kSparseWeights[6] = {0.6, 0.0, 0.0, 0.0, 0.4, 0.0};
  double weights[6];
  std::copy_n(options_.sparse ? kSparseWeights : kFullWeights, 6, weights);
  if (!allow_doors) weights[4] = 0.0;
  double total = 0;
  for (double w : weights) total += w;
  double s = s_begin + random_.Uniform(0, options_.object_gap_max);
  while (true) {
    bool placed = false;
    for (int attempt = 0; attempt < 4 && !placed; ++attempt) {
      double pick = random_.Uniform(0, total);
      int k = 0;
      while (k < 5 && pick >= weights[k]) pick -= weights[k++];
      const Furniture kind = static_cast<Furniture>(k);
      const double width = WidthOf(kind);
      if (s + width > s_end) continue;
      double top = 0;
      switch (kind) {
        case Furniture::kCabinet: top = AddCabinet(wall, s, width); break;
        case Furniture::kShelf: top = AddShelf(wall, s, width); break;
        case Furniture::kBoxStack: top = AddBoxStack(wall, s, width); break;
        case Furniture::kTable: top = AddTable(wall, s, width); break;
        case Furniture::kDoor: AddDoor(wall, s); top = options_.ceiling_height; break;
        case Furniture::kPoster: {
          const double z0 = random_.Uniform(1.0, 1.4), z1 = z0 + random_.Uniform(0.4, 0.9);
          AddPoster(wall, s, width, z0, std::min(z1, options_.ceiling_height - 0.2));
          top = options_.ceiling_height;
          break;
        }
      }
      // Low furniture gets a poster above it half of the time.
      if (top < 1.0 && random_.Bernoulli(0.5)) {
        const double z0 = top + random_.Uniform(0.3, 0.5);
        const double z1 = std::min(z0 + random_.Uniform(0.4, 0.8), options_.ceiling_height - 0.2);
        const double poster_width = random_.Uniform(0.3, 0.8) * width;
        AddPoster(wall, s + random_.Uniform(0, width - poster_width), poster_width, z0, z1);
      }
      s += width;
      placed = true;
    }
    if (!placed) break;
    s += options_.sparse ? random_.Uniform(kSparseGapMin, kSparseGapMax)
                         : random_.Uniform(options_.object_gap_min, options_.object_gap_max);
  }
}

double Builder::AddCabinet(const Wall& wall, double s0, double width) {
  const double depth = random_.Uniform(std::min(0.4, options_.max_object_depth), options_.max_object_depth);
  const double height = std::min(random_.Uniform(1.5, 2.0), options_.ceiling_height - 0.3);
  const std::vector<Eigen::Vector3d> normals = {wall.Along3(), wall.Inward3(), Eigen::Vector3d::UnitZ()};
  const double albedo = PickAlbedo(0.3, 0.95, normals, Background(&wall));
  const int id = scene_->AddObject("cabinet", /*obstacle=*/true);
  scene_->AddBox(id, wall.XY(s0 + 0.5 * width, kWallGap + 0.5 * depth), wall.Yaw(), 0,
                 {width, depth, height}, albedo, false);
  // One or two door leaves on the front, a little proud of it, a contrasting colour.
  const double door_albedo = PickAlbedo(0.2, 0.95, {wall.Inward3()}, {Shade(wall.Inward3(), albedo)});
  const int doors = scene_->AddObject("cabinet_door");
  const double d = kWallGap + depth + 0.004, z0 = 0.08, z1 = height - 0.04;
  const double left = s0 + 0.03, right = s0 + width - 0.03, gap = 0.012;
  std::vector<std::pair<double, double>> leaves;
  if (width < 0.65) {
    leaves = {{left, right}};
  } else {
    const double mid = 0.5 * (left + right);
    leaves = {{left, mid - 0.5 * gap}, {mid + 0.5 * gap, right}};
  }
  for (const auto& [a, b] : leaves) {
    scene_->AddPolygon(doors, {wall.At(a, d, z0), wall.At(b, d, z0), wall.At(b, d, z1), wall.At(a, d, z1)},
                       door_albedo, wall.Inward3());
  }
  return height;
}

double Builder::AddShelf(const Wall& wall, double s0, double width) {
  const double depth = random_.Uniform(std::min(0.28, options_.max_object_depth),
                                       std::min(0.4, options_.max_object_depth) - kCapOverhang);
  const double height = std::min(random_.Uniform(1.3, 1.9), options_.ceiling_height - 0.35);
  const double t = kBoardThickness;
  const std::vector<Eigen::Vector3d> normals = {wall.Along3(), wall.Inward3(), Eigen::Vector3d::UnitZ()};
  const double albedo = PickAlbedo(0.3, 0.95, normals, Background(&wall));
  const int id = scene_->AddObject("shelf", /*obstacle=*/true);
  const double yaw = wall.Yaw(), s1 = s0 + width, d0 = kWallGap, dm = d0 + 0.5 * depth;
  // Side panels, floor to `height`.
  scene_->AddBox(id, wall.XY(s0 + 0.5 * t, dm), yaw, 0, {t, depth, height}, albedo, false);
  scene_->AddBox(id, wall.XY(s1 - 0.5 * t, dm), yaw, 0, {t, depth, height}, albedo, false);
  // A top board overhanging the panels at the front and sides, set off the wall.
  const double cap_d0 = d0 - 0.01, cap_d1 = d0 + depth + kCapOverhang;
  scene_->AddBox(id, wall.XY(s0 + 0.5 * width, 0.5 * (cap_d0 + cap_d1)), yaw, height,
                 {width + 2 * kCapOverhang, cap_d1 - cap_d0, t}, albedo, true);
  // A back panel of another colour between the side panels, seen above each board.
  std::vector<double> own = {Shade(wall.Along3(), albedo), Shade(Eigen::Vector3d::UnitZ(), albedo),
                             Shade(wall.Inward3(), albedo)};
  const double back_albedo = PickAlbedo(0.1, 0.95, {wall.Inward3()}, own);
  const int back = scene_->AddObject("shelf_back");
  scene_->AddPolygon(back, {wall.At(s0 + t, d0, 0), wall.At(s1 - t, d0, 0), wall.At(s1 - t, d0, height),
                            wall.At(s0 + t, d0, height)},
                     back_albedo, wall.Inward3());
  // Boards, recessed a little from the front so that their fronts are not flush with the panels.
  const int boards = random_.UniformInt(2, 4);
  const double bottom = 0.08, spacing = (height - bottom) / (boards + 1);
  own.push_back(Shade(wall.Inward3(), back_albedo));
  for (int i = 0; i <= boards; ++i) {
    const double z = bottom + i * spacing;
    const double board_depth = depth - kBoardRecess;
    scene_->AddBox(id, wall.XY(s0 + 0.5 * width, d0 + 0.5 * board_depth), yaw, z, {width - 2 * t, board_depth, t},
                   albedo, true);
    // Items (books, bins) on some boards.
    if (!random_.Bernoulli(0.6)) continue;
    const double room = std::min(spacing - t - 0.05, 0.3);
    if (room < 0.08) continue;
    double s = s0 + t + random_.Uniform(0.02, 0.1);
    const int items = random_.UniformInt(1, 3);
    for (int k = 0; k < items; ++k) {
      const double w = random_.Uniform(0.08, 0.3);
      if (s + w > s1 - t - 0.02) break;
      const double item_depth = random_.Uniform(0.15, board_depth - 0.03);
      const double item_height = random_.Uniform(0.08, room);
      const double item_albedo = PickAlbedo(0.15, 0.95, normals, own);
      const int item = scene_->AddObject("shelf_item");
      scene_->AddBox(item, wall.XY(s + 0.5 * w, d0 + 0.01 + 0.5 * item_depth), yaw, z + t,
                     {w, item_depth, item_height}, item_albedo, false);
      s += w + random_.Uniform(0.01, 0.08);
    }
  }
  return height + t;
}

double Builder::StackBoxes(int object, const Eigen::Vector2d& centre, double yaw, double z,
                           const Eigen::Vector2d& base_size, double base_albedo, int count, double max_top,
                           const std::vector<double>& background) {
  Eigen::Vector2d size = base_size;
  std::vector<double> below = BoxShades(yaw, base_albedo);
  Eigen::Vector2d c = centre;
  for (int i = 0; i < count; ++i) {
    // Smaller than the box below so that, turned by up to 0.4 rad, it still stands on it.
    Eigen::Vector2d next(size.x() * random_.Uniform(0.45, 0.65), size.y() * random_.Uniform(0.45, 0.65));
    // Its diagonal must fit across the narrower side of the box below, whatever its turn.
    if (next.norm() > size.minCoeff()) next *= size.minCoeff() / next.norm();
    const double height = random_.Uniform(0.12, 0.35);
    if (z + height > max_top) return z;
    const double next_yaw = PickYaw(yaw, -0.4, 0.4);
    std::vector<double> avoid = below;
    for (double s : background) avoid.push_back(s);
    const double albedo = PickAlbedo(0.15, 0.95,
                                     {{std::cos(next_yaw), std::sin(next_yaw), 0},
                                      {-std::sin(next_yaw), std::cos(next_yaw), 0},
                                      Eigen::Vector3d::UnitZ()},
                                     avoid);
    const double room_x = 0.5 * (size.x() - next.norm()), room_y = 0.5 * (size.y() - next.norm());
    const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw)), ay(-ax.y(), ax.x());
    c += (room_x > 0 ? random_.Uniform(-room_x, room_x) : 0.0) * ax +
         (room_y > 0 ? random_.Uniform(-room_y, room_y) : 0.0) * ay;
    scene_->AddBox(object, c, next_yaw, z, {next.x(), next.y(), height}, albedo, false);
    z += height;
    size = next;
    yaw = next_yaw;
    below = BoxShades(yaw, albedo);
  }
  return z;
}

double Builder::AddBoxStack(const Wall& wall, double s0, double width) {
  const double depth = random_.Uniform(std::min(0.3, options_.max_object_depth), options_.max_object_depth);
  const double height = random_.Uniform(0.3, 0.6);
  const double yaw = wall.Yaw();
  const std::vector<Eigen::Vector3d> normals = {wall.Along3(), wall.Inward3(), Eigen::Vector3d::UnitZ()};
  const double albedo = PickAlbedo(0.3, 0.95, normals, Background(&wall));
  const int id = scene_->AddObject("box_stack", /*obstacle=*/true);
  scene_->AddBox(id, wall.XY(s0 + 0.5 * width, kWallGap + 0.5 * depth), yaw, 0, {width, depth, height}, albedo,
                 false);
  return StackBoxes(id, wall.XY(s0 + 0.5 * width, kWallGap + 0.5 * depth), yaw, height, {width, depth}, albedo,
                    random_.UniformInt(0, 2), 1.0, Background(&wall));
}

double Builder::AddTable(const Wall& wall, double s0, double width) {
  const double depth = random_.Uniform(std::min(0.4, options_.max_object_depth), options_.max_object_depth);
  const double height = random_.Uniform(0.72, 0.76), top = 0.035, leg = 0.05, inset = 0.03;
  const double yaw = wall.Yaw();
  const std::vector<Eigen::Vector3d> normals = {wall.Along3(), wall.Inward3(), Eigen::Vector3d::UnitZ()};
  const double albedo = PickAlbedo(0.3, 0.95, normals, Background(&wall));
  const int id = scene_->AddObject("table", /*obstacle=*/true);
  const double d_mid = kWallGap + 0.5 * depth;
  scene_->AddBox(id, wall.XY(s0 + 0.5 * width, d_mid), yaw, height - top, {width, depth, top}, albedo, true);
  for (int i = 0; i < 4; ++i) {
    const double s = (i % 2 == 0) ? s0 + inset + 0.5 * leg : s0 + width - inset - 0.5 * leg;
    const double d = (i < 2) ? kWallGap + inset + 0.5 * leg : kWallGap + depth - inset - 0.5 * leg;
    scene_->AddBox(id, wall.XY(s, d), yaw, 0, {leg, leg, height - top}, albedo, false);
  }
  if (random_.Bernoulli(0.6)) {
    const int boxes = scene_->AddObject("box");
    StackBoxes(boxes, wall.XY(s0 + 0.5 * width, d_mid), yaw, height, {width, depth}, albedo,
               random_.UniformInt(1, 2), 1.2, Background(&wall));
  }
  return height;
}

void Builder::AddDoor(const Wall& wall, double s0) {
  const double s1 = s0 + kDoorWidth + 2 * kJambWidth;
  const std::vector<Eigen::Vector3d> normals = {wall.Along3(), wall.Inward3(), Eigen::Vector3d::UnitZ()};
  const double frame_albedo = PickAlbedo(0.2, 0.95, normals, Background(&wall));
  const int frame = scene_->AddObject("door_frame");
  const double yaw = wall.Yaw();
  scene_->AddBox(frame, wall.XY(s0 + 0.5 * kJambWidth, 0.5 * kJambDepth), yaw, 0,
                 {kJambWidth, kJambDepth, kDoorHeight}, frame_albedo, false);
  scene_->AddBox(frame, wall.XY(s1 - 0.5 * kJambWidth, 0.5 * kJambDepth), yaw, 0,
                 {kJambWidth, kJambDepth, kDoorHeight}, frame_albedo, false);
  // The lintel overhangs the jambs (sides and front), so no two faces of the frame are flush.
  scene_->AddBox(frame, wall.XY(0.5 * (s0 + s1), 0.5 * kLintelDepth), yaw, kDoorHeight,
                 {s1 - s0 + 0.02, kLintelDepth, kJambWidth}, frame_albedo, true);
  std::vector<double> avoid = Background(&wall);
  for (double s : BoxShades(yaw, frame_albedo)) avoid.push_back(s);
  const double leaf_albedo = PickAlbedo(0.2, 0.9, {wall.Inward3()}, avoid);
  const double a = s0 + kJambWidth, b = s1 - kJambWidth;
  scene_->AddPolygon(scene_->AddObject("door"),
                     {wall.At(a, kFlatOffset, 0), wall.At(b, kFlatOffset, 0), wall.At(b, kFlatOffset, kDoorHeight),
                      wall.At(a, kFlatOffset, kDoorHeight)},
                     leaf_albedo, wall.Inward3());
}

void Builder::AddPoster(const Wall& wall, double s0, double width, double z0, double z1) {
  if (z1 - z0 < 0.1 || width < 0.1) return;
  const double albedo = PickAlbedo(0.05, 0.95, {wall.Inward3()}, {Shade(wall.Inward3(), wall_albedo_)});
  const int id = scene_->AddObject("poster");
  const double s1 = s0 + width, d = kFlatOffset;
  auto rectangle = [&](double a0, double a1, double b0, double b1, double depth, double a) {
    scene_->AddPolygon(id, {wall.At(a0, depth, b0), wall.At(a1, depth, b0), wall.At(a1, depth, b1), wall.At(a0, depth, b1)},
                       a, wall.Inward3());
  };
  const int variant = random_.UniformInt(0, 2);
  if (variant == 2) {
    // Quartered, like a window of four panes or a chart: two albedos in a 2 x 2 checker. The
    // centre is an X junction, the ends of the dividing lines on the border T junctions.
    const double other = PickAlbedo(0.05, 0.95, {wall.Inward3()},
                                    {Shade(wall.Inward3(), wall_albedo_), Shade(wall.Inward3(), albedo)});
    const double sm = s0 + width * random_.Uniform(0.35, 0.65), zm = z0 + (z1 - z0) * random_.Uniform(0.35, 0.65);
    rectangle(s0, sm, z0, zm, d, albedo);
    rectangle(sm, s1, z0, zm, d, other);
    rectangle(s0, sm, zm, z1, d, other);
    rectangle(sm, s1, zm, z1, d, albedo);
    return;
  }
  rectangle(s0, s1, z0, z1, d, albedo);
  if (variant == 0) return;
  // A framed picture: a second rectangle inside the first.
  const double margin = random_.Uniform(0.04, 0.1);
  if (width < 3 * margin || z1 - z0 < 3 * margin) return;
  const double inner = PickAlbedo(0.05, 0.95, {wall.Inward3()}, {Shade(wall.Inward3(), albedo)});
  rectangle(s0 + margin, s1 - margin, z0 + margin, z1 - margin, d + 0.003, inner);
}

void Builder::AddIsland(const Eigen::Vector2d& centre) {
  // A table turned a little, with boxes on it, and a box stack beside it.
  const double yaw = PickYaw(0, -0.25, 0.25);
  const double albedo = PickAlbedo(0.15, 0.95,
                                   {{std::cos(yaw), std::sin(yaw), 0}, {-std::sin(yaw), std::cos(yaw), 0},
                                    Eigen::Vector3d::UnitZ()},
                                   Background(nullptr));
  const int table = scene_->AddObject("table", /*obstacle=*/true);
  const Eigen::Vector2d table_centre = centre - Eigen::Vector2d(0.35, 0);
  const double length = 1.1, depth = 0.65, height = 0.74, top = 0.035, leg = 0.05, inset = 0.04;
  scene_->AddBox(table, table_centre, yaw, height - top, {length, depth, top}, albedo, true);
  const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw)), ay(-ax.y(), ax.x());
  for (int i = 0; i < 4; ++i) {
    const double u = (i % 2 == 0 ? -1 : 1) * (0.5 * length - inset - 0.5 * leg);
    const double v = (i < 2 ? -1 : 1) * (0.5 * depth - inset - 0.5 * leg);
    scene_->AddBox(table, table_centre + u * ax + v * ay, yaw, 0, {leg, leg, height - top}, albedo, false);
  }
  StackBoxes(scene_->AddObject("box"), table_centre, yaw, height, {length, depth}, albedo, 2, 1.3, Background(nullptr));

  const double stack_yaw = PickYaw(0, -0.6, 0.6);
  const double stack_albedo = PickAlbedo(0.15, 0.95,
                                         {{std::cos(stack_yaw), std::sin(stack_yaw), 0},
                                          {-std::sin(stack_yaw), std::cos(stack_yaw), 0}, Eigen::Vector3d::UnitZ()},
                                         Background(nullptr));
  const int stack = scene_->AddObject("box_stack", /*obstacle=*/true);
  const Eigen::Vector2d stack_centre = centre + Eigen::Vector2d(0.65, 0);
  const Eigen::Vector2d stack_size(0.4, 0.35);
  const double stack_height = random_.Uniform(0.4, 0.6);
  scene_->AddBox(stack, stack_centre, stack_yaw, 0, {stack_size.x(), stack_size.y(), stack_height}, stack_albedo,
                 false);
  StackBoxes(stack, stack_centre, stack_yaw, stack_height, stack_size, stack_albedo, 2, 1.2, Background(nullptr));
}

void Builder::BuildCorridor() {
  const double length = options_.corridor_length, half = 0.5 * options_.corridor_width;
  BuildShell({0, -half}, {length, half});
  scene_->lane_y = 0;
  const Wall south{{0, -half}, {1, 0}, {0, 1}, length};
  const Wall north{{0, half}, {1, 0}, {0, -1}, length};
  const Wall east{{length, -half}, {0, 1}, {-1, 0}, options_.corridor_width};
  FillWall(south, 0.3, length - 0.3, /*allow_doors=*/true);
  FillWall(north, 0.3, length - 0.3, /*allow_doors=*/true);
  // A door at the end of the corridor, straight ahead of the robot.
  const double door = kDoorWidth + 2 * kJambWidth;
  if (options_.corridor_width > door + 0.2) AddDoor(east, 0.5 * (options_.corridor_width - door));
  if (options_.ceiling_lights) {
    for (double x = 1.2; x + 0.6 < length; x += 2.4) AddCeilingLight({x, 0}, {1.2, 0.3});
  }
}

void Builder::BuildRoom() {
  const double lx = options_.room_length, ly = options_.room_width;
  BuildShell({0, 0}, {lx, ly});
  scene_->lane_y = 1.2;
  // Walls counter-clockwise seen from above; furniture keeps 0.6 m from the corners so that pieces
  // on neighbouring walls never meet.
  const Wall walls[4] = {{{0, 0}, {1, 0}, {0, 1}, lx},
                         {{lx, 0}, {0, 1}, {-1, 0}, ly},
                         {{lx, ly}, {-1, 0}, {0, -1}, lx},
                         {{0, ly}, {0, -1}, {1, 0}, ly}};
  const double corner = options_.max_object_depth + 0.1;
  for (const Wall& wall : walls) FillWall(wall, corner, wall.length - corner, /*allow_doors=*/true);
  if (options_.island && !options_.sparse) AddIsland({0.5 * lx, 0.5 * ly});
  if (options_.ceiling_lights) {
    for (double fx : {0.3, 0.7}) {
      for (double fy : {0.3, 0.7}) AddCeilingLight({fx * lx, fy * ly}, {1.2, 0.3});
    }
  }
}

}  // namespace

bool ParseSceneType(const std::string& name, SceneType* type) {
  if (name == "corridor") {
    *type = SceneType::kCorridor;
  } else if (name == "room") {
    *type = SceneType::kRoom;
  } else {
    return false;
  }
  return true;
}

const char* SceneTypeName(SceneType type) { return type == SceneType::kCorridor ? "corridor" : "room"; }

Status SceneOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("scene options: " + what); };
  if (!(ceiling_height >= 2.3 && ceiling_height <= 10)) {
    return error("ceiling_height must be in [2.3, 10] m (a door is 2.12 m high)");
  }
  if (!(max_object_depth >= 0.1 && max_object_depth <= 1.0)) return error("max_object_depth must be in [0.1, 1] m");
  if (!(object_gap_min >= 0 && object_gap_max >= object_gap_min)) {
    return error("need 0 <= object_gap_min <= object_gap_max");
  }
  if (!(min_contrast >= 0 && min_contrast < 0.2)) return error("min_contrast must be in [0, 0.2)");
  if (!(lighting.ambient >= 0 && lighting.diffuse >= 0 && lighting.ambient + lighting.diffuse <= 1.0 + 1e-12)) {
    return error("lighting: need ambient, diffuse >= 0 and ambient + diffuse <= 1");
  }
  if (!(std::abs(lighting.direction.norm() - 1) < 1e-9)) return error("lighting.direction must be a unit vector");
  const double min_width = 2 * (max_object_depth + kWallGap) + 0.6;
  if (type == SceneType::kCorridor) {
    if (!(corridor_width >= min_width && corridor_width <= 20)) {
      return error("corridor_width must be in [" + std::to_string(min_width) +
                   ", 20] m: furniture on both sides and 0.6 m between them");
    }
    if (!(corridor_length == 0 || (corridor_length >= 2 && corridor_length <= 500))) {
      return error("corridor_length must be in [2, 500] m (or 0: fitted to the trajectory by GenerateSequence)");
    }
  } else {
    if (!(room_length >= 3 && room_length <= 100 && room_width >= 3 && room_width <= 100)) {
      return error("room_length and room_width must be in [3, 100] m");
    }
  }
  return Status::Ok();
}

Status BuildScene(const SceneOptions& options, std::uint64_t seed, Scene* scene) {
  CHECK(scene != nullptr);
  SFM_RETURN_IF_ERROR(options.Check());
  if (options.type == SceneType::kCorridor && options.corridor_length == 0) {
    return Status::Error("scene options: corridor_length must be > 0 to build a corridor");
  }
  *scene = Scene();
  Builder builder(options, seed, scene);
  if (options.type == SceneType::kCorridor) {
    builder.BuildCorridor();
  } else {
    builder.BuildRoom();
  }
  return Status::Ok();
}

}  // namespace sfm
