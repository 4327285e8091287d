#include "benchmarks/colmap_ate/colmap_poses.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "backend/metrics/drift.h"

namespace sfm {

Status ReadColmapImagePoses(const std::string& images_txt,
                            std::map<std::string, Pose3>* world_T_camera_by_name) {
  world_T_camera_by_name->clear();
  std::ifstream in(images_txt);
  if (!in) return Status::Error(images_txt + ": cannot open");
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    long image_id = 0, camera_id = 0;
    double qw, qx, qy, qz, tx, ty, tz;
    std::string name;
    if (!(fields >> image_id >> qw >> qx >> qy >> qz >> tx >> ty >> tz >> camera_id >> name)) {
      return Status::Error(images_txt + ":" + std::to_string(line_number) +
                           ": expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
    }
    Eigen::Quaterniond q(qw, qx, qy, qz);
    if (!(std::abs(q.norm() - 1) < 1e-3) || !std::isfinite(tx + ty + tz)) {
      return Status::Error(images_txt + ":" + std::to_string(line_number) +
                           ": not a unit quaternion and a finite t");
    }
    q.normalize();
    const Pose3 camera_T_world(q, Eigen::Vector3d(tx, ty, tz));
    if (!world_T_camera_by_name->emplace(name, camera_T_world.Inverse()).second) {
      return Status::Error(images_txt + ":" + std::to_string(line_number) + ": image " + name +
                           " given twice");
    }
    // The image's 2D points: one line, empty when it has none.
    std::getline(in, line);
    ++line_number;
  }
  return Status::Ok();
}

Status ComputeFrameSubsetDrift(const Sequence& sequence, const std::map<int, Pose3>& world_T_camera_by_frame,
                               FrameSubsetDrift* drift) {
  if (!sequence.has_groundtruth) return Status::Error(sequence.directory + ": no groundtruth.txt");
  *drift = FrameSubsetDrift();
  drift->frames = static_cast<int>(sequence.frames.size());
  std::vector<Pose3> estimated, truth;
  for (const auto& [index, pose] : world_T_camera_by_frame) {
    if (index < 0 || index >= drift->frames) continue;
    drift->registered.push_back(index);
    estimated.push_back(pose);
    truth.push_back(*sequence.frames[index].world_T_base_groundtruth * sequence.calibration.base_T_camera);
  }
  drift->ate_m = AbsoluteTrajectoryError(estimated, truth);
  const SimilarityTrajectoryError sim3 = AbsoluteTrajectoryErrorSim3(estimated, truth);
  drift->ate_sim3_m = sim3.ate_m;
  drift->sim3_scale = sim3.scale;
  return Status::Ok();
}

}  // namespace sfm
