#include "sequences/importers/rosbag/bag_importer.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <queue>

#include "geometry/tum_io.h"
#include "sequences/importers/input_files.h"
#include "sequences/importers/rosbag/recording.h"
#include "sequences/importers/rosbag/ros2_messages.h"
#include "sequences/importers/sequence_output.h"
#include "util/atomic_file.h"
#include "util/number_text.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

constexpr std::int64_t kNanoseconds = 1000000000;

double Seconds(std::int64_t nanoseconds) { return static_cast<double>(nanoseconds) / 1e9; }

std::string SizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// One image message found in the first pass.
struct ImageStamp {
  std::int64_t stamp = 0;  // header stamp, ns
  int message = 0;         // index among the topic's messages, in storage order
};

// What the first pass keeps of each topic (by topic name).
struct TopicData {
  std::vector<ImageStamp> images;
  std::string image_frame;
  std::vector<RosStampedPose> poses;
  std::optional<RosCameraInfo> camera_info;
  std::vector<RosStampedPose> static_transforms;
  std::string decode_error;  // the first message that did not decode
};

bool IsImageType(const std::string& type) { return type == kRosImage || type == kRosCompressedImage; }

std::string TopicList(const Recording& bag, const std::vector<int>& indices) {
  std::string text;
  for (int index : indices) {
    const BagTopic& topic = bag.topics()[index];
    text += (text.empty() ? "" : ", ") + topic.name + " (" + topic.type + ", " + std::to_string(topic.count) +
            ")";
  }
  return text.empty() ? "none" : text;
}

// Picks the topic for one role: the one named, or the only candidate of the accepted types.
Status ChooseTopic(const Recording& bag, const std::string& role, const std::string& flag,
                   const std::string& named, const std::vector<std::string>& types,
                   const std::vector<int>& preferred, int* chosen) {
  std::vector<int> candidates;
  for (size_t i = 0; i < bag.topics().size(); ++i) {
    if (std::find(types.begin(), types.end(), bag.topics()[i].type) != types.end())
      candidates.push_back(static_cast<int>(i));
  }
  std::string type_text;
  for (const std::string& type : types) type_text += (type_text.empty() ? "" : " or ") + type;
  if (!named.empty()) {
    *chosen = bag.FindTopic(named);
    if (*chosen < 0) {
      return Status::Error(bag.path() + ": no topic " + named + " (" + role +
                           " topics: " + TopicList(bag, candidates) + ")");
    }
    const BagTopic& topic = bag.topics()[*chosen];
    if (std::find(types.begin(), types.end(), topic.type) == types.end()) {
      return Status::Error(bag.path() + ": " + named + ": type " + topic.type + ", the " + role +
                           " topic must be " + type_text);
    }
  } else {
    const std::vector<int>& pool = preferred.size() == 1 ? preferred : candidates;
    if (pool.empty()) return Status::Error(bag.path() + ": no " + role + " topic (" + type_text + ")");
    if (pool.size() > 1) {
      return Status::Error(bag.path() + ": " + std::to_string(pool.size()) + " " + role +
                           " topics, choose one with --" + flag + ": " + TopicList(bag, pool));
    }
    *chosen = pool[0];
  }
  const BagTopic& topic = bag.topics()[*chosen];
  if (!topic.problem.empty()) return Status::Error(bag.path() + ": " + topic.name + ": " + topic.problem);
  if (topic.count == 0)
    return Status::Error(bag.path() + ": " + topic.name + ": the " + role + " topic is empty");
  return Status::Ok();
}

// The pose of `stamp` on a trajectory sorted by stamp: exact at a sample, else interpolated
// (linear translation, slerp) between the two around it when they are at most max_gap apart.
// nullopt outside the trajectory or in a gap.
std::optional<Pose3> PoseAt(const std::vector<RosStampedPose>& trajectory, std::int64_t stamp,
                            std::int64_t max_gap) {
  const auto after =
      std::lower_bound(trajectory.begin(), trajectory.end(), stamp,
                       [](const RosStampedPose& pose, std::int64_t t) { return pose.header.stamp < t; });
  if (after == trajectory.end()) return std::nullopt;
  if (after->header.stamp == stamp) return after->parent_T_child;
  if (after == trajectory.begin()) return std::nullopt;
  const RosStampedPose& before = *(after - 1);
  const std::int64_t gap = after->header.stamp - before.header.stamp;
  if (gap > max_gap) return std::nullopt;
  return InterpolatePose(before.parent_T_child, after->parent_T_child,
                         static_cast<double>(stamp - before.header.stamp) / static_cast<double>(gap));
}

// base_T_camera from the static transforms: a path through the tree of frames, each edge
// parent_T_child walked either way.
std::optional<Pose3> StaticTransform(const std::vector<RosStampedPose>& transforms, const std::string& base,
                                     const std::string& camera) {
  if (base == camera) return Pose3::Identity();
  std::map<std::string, std::vector<std::pair<std::string, Pose3>>> edges;
  for (const RosStampedPose& t : transforms) {
    edges[t.header.frame_id].push_back({t.child_frame_id, t.parent_T_child});
    edges[t.child_frame_id].push_back({t.header.frame_id, t.parent_T_child.Inverse()});
  }
  std::map<std::string, Pose3> base_T;
  base_T[base] = Pose3::Identity();
  std::queue<std::string> open;
  open.push(base);
  while (!open.empty()) {
    const std::string frame = open.front();
    open.pop();
    if (frame == camera) return base_T[frame];
    for (const auto& [next, frame_T_next] : edges[frame]) {
      if (base_T.count(next) != 0) continue;
      base_T[next] = base_T[frame] * frame_T_next;
      open.push(next);
    }
  }
  return std::nullopt;
}

// The camera of a CameraInfo message (SPEC: radtan from plumb_bob, equidistant as it is).
Status CameraFromInfo(const RosCameraInfo& info, const std::string& where, Camera* camera) {
  camera->width = static_cast<int>(info.width);
  camera->height = static_cast<int>(info.height);
  camera->fx = info.k[0];
  camera->cx = info.k[2];
  camera->fy = info.k[4];
  camera->cy = info.k[5];
  for (double value : info.k) {
    if (!std::isfinite(value)) return Status::Error(where + ": K is not finite");
  }
  if (!(camera->fx > 0 && camera->fy > 0) || camera->width <= 0 || camera->height <= 0) {
    return Status::Error(where + ": no calibration (K has fx " + ShortestNumberText(camera->fx) + ", fy " +
                         ShortestNumberText(camera->fy) + ", size " +
                         SizeText(camera->width, camera->height) + ")");
  }
  for (double value : info.d) {
    if (!std::isfinite(value)) return Status::Error(where + ": D is not finite");
  }
  const std::string& model = info.distortion_model;
  const bool all_zero = std::all_of(info.d.begin(), info.d.end(), [](double d) { return d == 0; });
  if (model == "plumb_bob" || (all_zero && model != "equidistant")) {
    if (!all_zero && info.d.size() != 4 && info.d.size() != 5) {
      return Status::Error(where + ": plumb_bob with " + std::to_string(info.d.size()) +
                           " coefficients (expected k1 k2 p1 p2 [k3])");
    }
    for (size_t i = 0; i < info.d.size() && i < 5; ++i) camera->distortion[i] = info.d[i];
    return Status::Ok();
  }
  if (model == "equidistant") {
    if (info.d.size() != 4) {
      return Status::Error(where + ": equidistant with " + std::to_string(info.d.size()) +
                           " coefficients (expected k1 k2 k3 k4)");
    }
    camera->model = DistortionModel::kEquidistant;
    for (size_t i = 0; i < 4; ++i) camera->distortion[i] = info.d[i];
    return Status::Ok();
  }
  if (model == "rational_polynomial") {
    return Status::Error(where + ": distortion model rational_polynomial (" + std::to_string(info.d.size()) +
                         " coefficients) is not supported: the sequence format has radtan (plumb_bob) and "
                         "equidistant; recalibrate with one of them");
  }
  return Status::Error(where + ": unknown distortion model '" + model +
                       "' (expected plumb_bob or equidistant)");
}

// An Image message as an 8-bit OpenCV image (grey or BGR). mono16 is shifted right by `shift`
// bits, chosen on the first image so that its brightest pixel fits 8 bits.
Status RawImageToMat(const RosImage& image, const std::string& where, int* mono16_shift, cv::Mat* out) {
  std::string encoding = image.encoding;
  if (encoding == "8UC1") encoding = "mono8";
  if (encoding == "8UC3") encoding = "bgr8";
  if (encoding == "16UC1") encoding = "mono16";
  int channels = 0, depth_bytes = 1;
  if (encoding == "mono8") {
    channels = 1;
  } else if (encoding == "rgb8" || encoding == "bgr8") {
    channels = 3;
  } else if (encoding == "rgba8" || encoding == "bgra8") {
    channels = 4;
  } else if (encoding == "mono16") {
    channels = 1, depth_bytes = 2;
  } else {
    return Status::Error(where + ": image encoding '" + image.encoding +
                         "' is not supported (mono8, mono16, rgb8, bgr8, rgba8, bgra8)");
  }
  const std::uint64_t row = std::uint64_t{image.width} * channels * depth_bytes;
  if (image.width == 0 || image.height == 0 || image.step < row ||
      image.data.size() < std::uint64_t{image.step} * (image.height - 1) + row) {
    return Status::Error(where + ": image data of " + std::to_string(image.data.size()) +
                         " bytes does not hold " + std::to_string(image.height) + " rows of " +
                         std::to_string(row) + " bytes (step " + std::to_string(image.step) + ")");
  }
  const int type = depth_bytes == 2 ? CV_16UC1 : CV_MAKETYPE(CV_8U, channels);
  cv::Mat view(static_cast<int>(image.height), static_cast<int>(image.width), type,
               const_cast<std::uint8_t*>(image.data.data()), image.step);
  cv::Mat copy = view.clone();
  if (encoding == "mono16") {
    const std::uint16_t probe = 1;
    const bool host_big_endian = *reinterpret_cast<const std::uint8_t*>(&probe) == 0;
    if (image.big_endian != host_big_endian) {
      for (int r = 0; r < copy.rows; ++r) {
        std::uint16_t* p = copy.ptr<std::uint16_t>(r);
        for (int c = 0; c < copy.cols; ++c) p[c] = static_cast<std::uint16_t>((p[c] >> 8) | (p[c] << 8));
      }
    }
    if (*mono16_shift < 0) {
      double max_value = 0;
      cv::minMaxLoc(copy, nullptr, &max_value);
      int bits = 0;
      while (bits < 16 && (1 << bits) <= max_value) ++bits;
      *mono16_shift = std::max(0, bits - 8);
    }
    // A shift (not a rounding scale), so that 8-bit values stored as v << s come back exactly.
    out->create(copy.rows, copy.cols, CV_8UC1);
    for (int r = 0; r < copy.rows; ++r) {
      const std::uint16_t* p = copy.ptr<std::uint16_t>(r);
      std::uint8_t* q = out->ptr<std::uint8_t>(r);
      for (int c = 0; c < copy.cols; ++c)
        q[c] = static_cast<std::uint8_t>(std::min(255, p[c] >> *mono16_shift));
    }
    return Status::Ok();
  }
  if (encoding == "rgb8") {
    cv::cvtColor(copy, *out, cv::COLOR_RGB2BGR);
  } else if (encoding == "rgba8") {
    cv::cvtColor(copy, *out, cv::COLOR_RGBA2BGR);
  } else if (encoding == "bgra8") {
    cv::cvtColor(copy, *out, cv::COLOR_BGRA2BGR);
  } else {
    *out = copy;
  }
  return Status::Ok();
}

}  // namespace

Status BagImportOptions::Check() const {
  if (every < 1) return Status::Error("--every must be >= 1");
  if (!(min_motion >= 0) || !(min_rotation >= 0))
    return Status::Error("--min_motion and --min_rotation must be >= 0");
  if (!(start_time >= 0) || !(end_time > start_time)) {
    return Status::Error("the time window needs 0 <= --start_time < --end_time");
  }
  if (!(max_odometry_gap > 0)) return Status::Error("--max_odometry_gap must be > 0 s");
  return scale.Check();
}

Status ImportRecording(Recording* recording, const BagImportOptions& options, const std::string& output_dir,
                       BagImportSummary* summary) {
  SFM_RETURN_IF_ERROR(options.Check());
  *summary = BagImportSummary();
  Recording& bag = *recording;

  // Pass 1: every topic the importer may use, images by their headers only.
  std::map<std::string, TopicData> data;  // by topic name
  SFM_RETURN_IF_ERROR(bag.ReadMessages([&](const BagTopic& topic, const RecordedMessage& message) {
    if (!topic.problem.empty()) return Status::Ok();
    TopicData& kept = data[topic.name];
    if (!kept.decode_error.empty()) return Status::Ok();
    Status status;
    if (IsImageType(topic.type)) {
      RosHeader header;
      status = message.ImageHeader(&header);
      if (status.ok()) {
        if (kept.images.empty()) kept.image_frame = header.frame_id;
        kept.images.push_back({header.stamp, static_cast<int>(topic.count - 1)});
      }
    } else if (IsRosPoseType(topic.type)) {
      RosStampedPose pose;
      status = message.StampedPose(&pose);
      if (status.ok()) kept.poses.push_back(pose);
    } else if (topic.type == kRosCameraInfo) {
      RosCameraInfo info;
      status = message.CameraInfo(&info);
      if (status.ok() && !kept.camera_info) kept.camera_info = info;
    } else if (topic.type == kRosTfMessage && topic.name == "/tf_static") {
      std::vector<RosStampedPose> transforms;
      status = message.TfMessage(&transforms);
      kept.static_transforms.insert(kept.static_transforms.end(), transforms.begin(), transforms.end());
    }
    if (!status.ok()) kept.decode_error = status.message();
    return Status::Ok();
  }));

  // The topics.
  int image_index = -1, odometry_index = -1, info_index = -1, truth_index = -1;
  SFM_RETURN_IF_ERROR(ChooseTopic(bag, "image", "image_topic", options.image_topic,
                                  {kRosImage, kRosCompressedImage}, {}, &image_index));
  const BagTopic image_topic = bag.topics()[image_index];
  {
    std::vector<int> odometry_types;
    for (size_t i = 0; i < bag.topics().size(); ++i) {
      if (bag.topics()[i].type == kRosOdometry) odometry_types.push_back(static_cast<int>(i));
    }
    // Odometry messages first; stamped poses or transforms when the bag has no Odometry topic.
    const std::vector<std::string> types =
        odometry_types.empty() && options.odometry_topic.empty()
            ? std::vector<std::string>{kRosPoseStamped, kRosTransformStamped}
            : std::vector<std::string>{kRosOdometry, kRosPoseStamped, kRosTransformStamped};
    SFM_RETURN_IF_ERROR(ChooseTopic(bag, "odometry", "odometry_topic", options.odometry_topic, types,
                                    odometry_types.size() == 1 ? odometry_types : std::vector<int>{},
                                    &odometry_index));
  }
  {
    // Several CameraInfo topics: the one beside the image topic (same namespace) when there is one.
    std::vector<int> beside;
    const std::string image_namespace = fs::path(image_topic.name).parent_path().string();
    for (size_t i = 0; i < bag.topics().size(); ++i) {
      const BagTopic& topic = bag.topics()[i];
      if (topic.type == kRosCameraInfo && fs::path(topic.name).parent_path().string() == image_namespace) {
        beside.push_back(static_cast<int>(i));
      }
    }
    if (!options.calibration) {
      SFM_RETURN_IF_ERROR(ChooseTopic(bag, "camera_info", "camera_info_topic", options.camera_info_topic,
                                      {kRosCameraInfo}, beside, &info_index));
    }
  }
  if (!options.groundtruth_topic.empty()) {
    SFM_RETURN_IF_ERROR(ChooseTopic(bag, "ground-truth", "groundtruth_topic", options.groundtruth_topic,
                                    {kRosOdometry, kRosPoseStamped, kRosTransformStamped}, {}, &truth_index));
  }
  for (int index : {image_index, odometry_index, info_index, truth_index}) {
    if (index >= 0 && !data[bag.topics()[index].name].decode_error.empty()) {
      return Status::Error(data[bag.topics()[index].name].decode_error);
    }
  }
  summary->image_topic = image_topic.name;
  summary->odometry_topic = bag.topics()[odometry_index].name;
  summary->camera_info_topic = info_index >= 0 ? bag.topics()[info_index].name : "--calibration";
  if (truth_index >= 0) summary->groundtruth_topic = bag.topics()[truth_index].name;
  const std::string image_where = bag.path() + ": " + image_topic.name;
  const std::string odometry_where = bag.path() + ": " + summary->odometry_topic;

  // The camera.
  Camera camera;
  std::string camera_info_frame;
  if (options.calibration) {
    camera = options.calibration->camera;
  } else {
    const RosCameraInfo& info = *data[summary->camera_info_topic].camera_info;
    SFM_RETURN_IF_ERROR(CameraFromInfo(info, bag.path() + ": " + summary->camera_info_topic, &camera));
    camera_info_frame = info.header.frame_id;
  }

  // The frames: the window, the odometry at each stamp, every N-th, then the keyframe motion.
  std::vector<ImageStamp> images = data[image_topic.name].images;
  std::stable_sort(images.begin(), images.end(),
                   [](const ImageStamp& a, const ImageStamp& b) { return a.stamp < b.stamp; });
  summary->images_on_topic = static_cast<int>(images.size());
  std::vector<RosStampedPose> odometry = data[summary->odometry_topic].poses;
  std::stable_sort(odometry.begin(), odometry.end(), [](const RosStampedPose& a, const RosStampedPose& b) {
    return a.header.stamp < b.header.stamp;
  });
  const std::int64_t first_stamp = images.front().stamp;
  std::vector<ImageStamp> windowed;
  for (const ImageStamp& image : images) {
    const double t = Seconds(image.stamp - first_stamp);
    if (t >= options.start_time && t <= options.end_time) {
      windowed.push_back(image);
    } else {
      ++summary->outside_window;
    }
  }
  if (windowed.empty()) {
    return Status::Error(image_where + ": no image in the time window [" +
                         ShortestNumberText(options.start_time) + ", " +
                         ShortestNumberText(options.end_time) + "] s after the first (the topic spans " +
                         ShortestNumberText(Seconds(images.back().stamp - first_stamp)) + " s)");
  }
  const std::int64_t max_gap =
      static_cast<std::int64_t>(std::llround(options.max_odometry_gap * kNanoseconds));
  const double window_start = Seconds(windowed.front().stamp - first_stamp);
  const double window_end = Seconds(windowed.back().stamp - first_stamp);
  if (odometry.front().header.stamp > windowed.front().stamp + max_gap) {
    return Status::Error(odometry_where + ": odometry starts at " +
                         ShortestNumberText(Seconds(odometry.front().header.stamp - first_stamp)) +
                         " s, after the images (from " + ShortestNumberText(window_start) + " s on " +
                         image_topic.name + "); start later with --start_time");
  }
  if (odometry.back().header.stamp < windowed.back().stamp - max_gap) {
    return Status::Error(odometry_where + ": odometry stops at " +
                         ShortestNumberText(Seconds(odometry.back().header.stamp - first_stamp)) +
                         " s, before the images (to " + ShortestNumberText(window_end) + " s on " +
                         image_topic.name + "); end earlier with --end_time");
  }
  struct Kept {
    ImageStamp image;
    Pose3 world_T_base;
  };
  std::vector<Kept> kept;
  int with_odometry = 0;
  for (const ImageStamp& image : windowed) {
    const std::optional<Pose3> pose = PoseAt(odometry, image.stamp, max_gap);
    if (!pose) {
      ++summary->in_odometry_gaps;
      continue;
    }
    if (with_odometry++ % options.every != 0) {
      ++summary->dropped_by_every;
      continue;
    }
    if ((options.min_motion > 0 || options.min_rotation > 0) && !kept.empty()) {
      const Pose3& last = kept.back().world_T_base;
      const bool moved =
          (pose->translation - last.translation).norm() >= options.min_motion && options.min_motion > 0;
      const bool turned =
          RotationAngle(pose->rotation, last.rotation) >= options.min_rotation && options.min_rotation > 0;
      if (!moved && !turned) {
        ++summary->dropped_by_motion;
        continue;
      }
    }
    kept.push_back({image, *pose});
  }
  if (kept.size() < 2) {
    return Status::Error(image_where + ": " + std::to_string(kept.size()) + " image(s) kept of " +
                         std::to_string(images.size()) + " (" + std::to_string(summary->outside_window) +
                         " outside the time window, " + std::to_string(summary->in_odometry_gaps) +
                         " in odometry gaps, " + std::to_string(summary->dropped_by_every) + " by --every, " +
                         std::to_string(summary->dropped_by_motion) +
                         " by the keyframe motion); a sequence needs 2");
  }
  std::vector<Pose3> truth;
  if (truth_index >= 0) {
    std::vector<RosStampedPose> poses = data[summary->groundtruth_topic].poses;
    std::stable_sort(poses.begin(), poses.end(), [](const RosStampedPose& a, const RosStampedPose& b) {
      return a.header.stamp < b.header.stamp;
    });
    for (const Kept& frame : kept) {
      const std::optional<Pose3> pose = PoseAt(poses, frame.image.stamp, max_gap);
      if (!pose) {
        return Status::Error(bag.path() + ": " + summary->groundtruth_topic +
                             ": no ground truth at the image of " +
                             ShortestNumberText(Seconds(frame.image.stamp - first_stamp)) + " s (it covers " +
                             ShortestNumberText(Seconds(poses.front().header.stamp - first_stamp)) + " to " +
                             ShortestNumberText(Seconds(poses.back().header.stamp - first_stamp)) +
                             " s); narrow the window with --start_time / --end_time");
      }
      truth.push_back(*pose);
    }
  }

  // T_base_camera.
  std::string base_frame = options.base_frame, camera_frame = options.camera_frame;
  if (base_frame.empty()) base_frame = odometry.front().child_frame_id;
  if (camera_frame.empty()) camera_frame = data[image_topic.name].image_frame;
  if (camera_frame.empty()) camera_frame = camera_info_frame;
  Pose3 base_T_camera = Pose3::Identity();
  std::string transform_note =
      "T_base_camera: identity (base and camera frame '" + camera_frame + "' are one)";
  if (options.calibration) {
    base_T_camera = options.calibration->base_T_camera;
    transform_note = "T_base_camera: --calibration";
  } else if (base_frame.empty()) {
    return Status::Error(odometry_where +
                         ": the odometry names no base frame (PoseStamped); give --base_frame");
  } else if (base_frame != camera_frame) {
    std::vector<RosStampedPose> transforms;
    if (bag.FindTopic("/tf_static") >= 0) {
      if (!data["/tf_static"].decode_error.empty()) return Status::Error(data["/tf_static"].decode_error);
      transforms = data["/tf_static"].static_transforms;
    }
    const std::optional<Pose3> found = StaticTransform(transforms, base_frame, camera_frame);
    if (!found) {
      return Status::Error(bag.path() + ": /tf_static: no transform from the base frame '" + base_frame +
                           "' to the camera frame '" + camera_frame + "' (" +
                           std::to_string(transforms.size()) +
                           " static transforms); name the frames with --base_frame / --camera_frame");
    }
    base_T_camera = *found;
    transform_note = "T_base_camera: /tf_static, from '" + base_frame + "' to '" + camera_frame + "'";
  }

  // Pass 2: the kept images, written into the temporary directory.
  const fs::path target = NormalisedTarget(output_dir);
  fs::path temporary_path;
  SFM_RETURN_IF_ERROR(PrepareOutputDirectory(target, options.overwrite, &temporary_path));
  TemporaryDirectory temporary(temporary_path);
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((temporary.path() / "images").string()));
  const cv::Size size = ScaledImageSize(camera.width, camera.height, options.scale);
  std::map<int, int> frame_of_message;
  for (size_t i = 0; i < kept.size(); ++i) frame_of_message[kept[i].image.message] = static_cast<int>(i);
  int written = 0;
  cv::Size first_size;  // of the first image read: all must have it
  SFM_RETURN_IF_ERROR(bag.ReadMessages([&](const BagTopic& topic, const RecordedMessage& message) {
    if (topic.name != image_topic.name) return Status::Ok();
    const auto found = frame_of_message.find(static_cast<int>(topic.count - 1));
    if (found == frame_of_message.end()) return Status::Ok();
    const std::string what = image_where + ": message " + std::to_string(topic.count - 1);
    cv::Mat image;
    if (topic.type == kRosImage) {
      RosImage raw;
      SFM_RETURN_IF_ERROR(message.Image(&raw));
      SFM_RETURN_IF_ERROR(RawImageToMat(raw, what, &summary->mono16_shift, &image));
    } else {
      RosCompressedImage compressed;
      SFM_RETURN_IF_ERROR(message.CompressedImage(&compressed));
      cv::Mat decoded;
      SFM_RETURN_IF_ERROR(DecodeImageBytes(what + " (" + compressed.format + ")", compressed.data,
                                           cv::IMREAD_ANYCOLOR | cv::IMREAD_ANYDEPTH, &decoded));
      if (decoded.depth() == CV_16U && decoded.channels() == 1) {
        RosImage raw;
        raw.width = decoded.cols, raw.height = decoded.rows, raw.encoding = "mono16";
        raw.step = decoded.cols * 2;
        raw.big_endian = false;
        const cv::Mat continuous = decoded.clone();
        raw.data.assign(continuous.data, continuous.data + continuous.total() * 2);
        SFM_RETURN_IF_ERROR(RawImageToMat(raw, what, &summary->mono16_shift, &image));
      } else if (decoded.depth() != CV_8U) {
        return Status::Error(what + ": compressed image of depth other than 8 or 16 bits");
      } else if (decoded.channels() == 4) {
        cv::cvtColor(decoded, image, cv::COLOR_BGRA2BGR);
      } else {
        image = decoded;
      }
    }
    if (first_size.empty()) first_size = image.size();
    if (image.size() != first_size) {
      return Status::Error(what + ": image is " + SizeText(image.cols, image.rows) + ", earlier ones " +
                           SizeText(first_size.width, first_size.height) + " (images of changing size)");
    }
    if (image.cols != camera.width || image.rows != camera.height) {
      return Status::Error(what + ": image is " + SizeText(image.cols, image.rows) + ", " +
                           summary->camera_info_topic + " says " + SizeText(camera.width, camera.height));
    }
    if (image.size() != size) cv::resize(cv::Mat(image), image, size, 0, 0, cv::INTER_AREA);
    char name[32];
    std::snprintf(name, sizeof(name), "images/%06d.png", found->second);
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", image, png)) return Status::Error(what + ": PNG encoding failed");
    SFM_RETURN_IF_ERROR(
        WriteFileAtomically((temporary.path() / name).string(), std::string(png.begin(), png.end())));
    ++written;
    return Status::Ok();
  }));
  if (written != static_cast<int>(kept.size())) {
    return Status::Error(image_where + ": " + std::to_string(written) + " of " + std::to_string(kept.size()) +
                         " images read back (the bag changed while it was read?)");
  }

  // The text files.
  const fs::path& root = temporary.path();
  std::string image_list =
      "# timestamp image (imported from a bag by import_sequence; see import_notes.txt)\n";
  std::vector<StampedPose> odometry_poses, truth_poses;
  for (size_t i = 0; i < kept.size(); ++i) {
    const double t = Seconds(kept[i].image.stamp);
    char name[32];
    std::snprintf(name, sizeof(name), "images/%06zu.png", i);
    image_list += ShortestNumberText(t) + " " + name + "\n";
    odometry_poses.push_back({t, kept[i].world_T_base});
    if (!truth.empty()) truth_poses.push_back({t, truth[i]});
  }
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "images.txt").string(), image_list));
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "odometry.txt").string(), odometry_poses));
  if (!truth_poses.empty())
    SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "groundtruth.txt").string(), truth_poses));
  Calibration calibration;
  calibration.camera = ScaleCamera(camera, size);
  calibration.base_T_camera = base_T_camera;
  if (options.odometry_noise) {
    calibration.odometry_noise = *options.odometry_noise;
    calibration.odometry_noise_given = true;
  }
  const std::string yaml = (root / "sequence.yaml").string();
  SFM_RETURN_IF_ERROR(WriteCalibration(yaml, calibration));
  summary->frames = static_cast<int>(kept.size());
  std::string notes = "# How this sequence was imported (import_sequence; see docs/importers.md)\n";
  notes += "format: " + bag.format() + ", " + bag.path() + "\n";
  notes += "images: " + image_topic.name + " (" + image_topic.type + "), " + std::to_string(kept.size()) +
           " of " + std::to_string(images.size()) + " (" + std::to_string(summary->outside_window) +
           " outside the window, " + std::to_string(summary->in_odometry_gaps) + " in odometry gaps, " +
           std::to_string(summary->dropped_by_every) + " by --every, " +
           std::to_string(summary->dropped_by_motion) +
           " by the keyframe motion); timestamps: header stamps, seconds\n";
  if (summary->mono16_shift >= 0)
    notes += "mono16 images: shifted right by " + std::to_string(summary->mono16_shift) + " bits\n";
  if (size.width != camera.width) {
    notes += "images scaled from " + SizeText(camera.width, camera.height) + " to " +
             SizeText(size.width, size.height) + "\n";
  }
  notes += "camera: " + summary->camera_info_topic + " (" + DistortionModelName(camera.model) + ")\n";
  notes += "odometry: " + summary->odometry_topic + ", world_T_base interpolated at the image stamps\n";
  if (!truth.empty())
    notes += "ground truth: " + summary->groundtruth_topic + ", interpolated at the image stamps\n";
  notes += transform_note + "\n";
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "import_notes.txt").string(), notes));
  SFM_RETURN_IF_ERROR(MoveIntoPlace(&temporary, target));
  LOG(INFO) << "bag: wrote " << kept.size() << " frames of " << SizeText(size.width, size.height) << " from "
            << image_topic.name << " to " << target.string();
  return Status::Ok();
}

}  // namespace sfm
