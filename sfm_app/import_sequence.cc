// import_sequence: a real data set with ground-truth cameras as a SPEC sequence directory (SPEC
// section 1), with odometry simulated from the true poses by a stated, seeded noise model.
//
//   build/bin/import_sequence --format vgg|strecha|tum --input <data set dir> --output <sequence dir>
//   build/bin/import_sequence --format euroc --input <ASL folder> --odometry <file> --output <sequence dir>
//   build/bin/import_sequence --format rosbag2 --input <bag folder, .mcap or .db3> --output <sequence dir>
//   build/bin/import_sequence --format rosbag --input <ROS 1 .bag file> --output <sequence dir>
//
// EuRoC folders and bags give the robot's own odometry: nothing is simulated for them.
//
// docs/importers.md describes each format, the noise model and the figures measured on the data.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "sequences/importers/calibration_files.h"
#include "sequences/importers/euroc_importer.h"
#include "sequences/importers/imported_sequence.h"
#include "sequences/importers/rosbag/bag_importer.h"
#include "sequences/importers/rosbag/rosbag1_recording.h"
#include "sequences/importers/strecha_importer.h"
#include "sequences/importers/tum_importer.h"
#include "sequences/importers/vgg_importer.h"

namespace {
const sfm::SequenceWriteOptions kDefaults;
}  // namespace

DEFINE_string(
    format, "",
    "Data set format: 'vgg' (Oxford VGG multi-view: <name>.NNN.pgm, <name>.NNN.P, <name>.p3d), "
    "'strecha' (images/*.jpg, gt_dense_cameras/*.camera), 'tum' (TUM RGB-D: rgb.txt, rgb/, "
    "groundtruth.txt), 'euroc' (EuRoC / ASL: cam0/data.csv, cam0/data/, cam0/sensor.yaml, with the robot's "
    "--odometry), 'rosbag2' (a ROS 2 bag: its folder with metadata.yaml, or one .mcap or .db3 file) or "
    "'rosbag' (a ROS 1 .bag file). Required.");
DEFINE_string(input, "", "Data set directory (rosbag2: the bag folder or storage file; rosbag: the .bag file). Required.");
DEFINE_string(output, "",
              "Sequence directory to create (written to a temporary sibling and renamed into place). Required.");
DEFINE_bool(overwrite, false, "Replace --output when it exists and is not empty.");
DEFINE_uint64(seed, kDefaults.seed, "Seed of the simulated odometry noise (same seed, same odometry.txt).");
DEFINE_double(scale, kDefaults.scale.scale,
              "Image scale factor in (0, 1] for every axis, K scaled with it; 0: use --max_width.");
DEFINE_int32(max_width, kDefaults.scale.max_width,
             "When --scale is 0, images wider than this many pixels are scaled down to it; 0 keeps the size.");
DEFINE_double(odometry_scale_error, kDefaults.odometry.scale_error,
              "Odometry scale error: each step's translation is reported (1 + this) times too long.");
DEFINE_double(odometry_distance_sigma, kDefaults.odometry.distance_sigma,
              "Odometry translation noise per step, Gaussian sigma as a fraction of the step's length.");
DEFINE_double(odometry_rotation_sigma, kDefaults.odometry.rotation_sigma,
              "Odometry rotation noise per step, Gaussian sigma of each rotation-vector component, radians "
              "(0.0052 rad = 0.3 deg).");
DEFINE_double(
    odometry_heading_bias, kDefaults.odometry.rotation_bias,
    "Odometry heading drift per step: a rotation about the camera's y axis, radians (make_sequence's "
    "--odometry_heading_bias for the generated robot).");
DEFINE_double(odometry_noise_scale, 1,
              "Multiplies every odometry noise term above (scale error, distance sigma, rotation sigma, "
              "heading bias), after they are set; >= 0 (0: noise-free odometry, 3: three times the noise).");
DEFINE_bool(
    vgg_refit_poses, sfm::VggImportOptions().refit_poses,
    "vgg: re-estimate the poses for the sequence's one K (by --vgg_refit); false keeps R, C of each P's "
    "own decomposition with the median of the frames' K, which reproject worse.");
DEFINE_string(
    vgg_refit, "joint",
    "vgg: how the poses are re-estimated: 'joint' (all poses and the data set's 3D points fitted together "
    "to its matched corners, <name>.nview-corners, for the median K) or 'pnp' (each pose alone by PnP onto "
    "the fixed 3D points as its P projects them).");
DEFINE_bool(
    vgg_refit_focal, sfm::VggImportOptions().refit_focal,
    "vgg, --vgg_refit=joint: also estimate fx, fy (self-calibration; nearly unobservable on Corridor).");
DEFINE_bool(
    vgg_refit_principal_point, sfm::VggImportOptions().refit_principal_point,
    "vgg, --vgg_refit=joint: also estimate cx, cy (self-calibration; nearly unobservable on Corridor).");
DEFINE_bool(vgg_refit_k1, sfm::VggImportOptions().refit_radial_k1,
            "vgg, --vgg_refit=joint: also estimate a radial distortion term k1 (written to sequence.yaml).");
DEFINE_double(
    vgg_k1, sfm::VggImportOptions().k1,
    "vgg, --vgg_refit=joint: the images' radial distortion k1 (OpenCV's model) when known from elsewhere, "
    "e.g. a separate calibration; held in the refit and written to sequence.yaml. 0: none.");
DEFINE_bool(
    vgg_k1_from_lines, sfm::VggImportOptions().k1_from_lines,
    "vgg, --vgg_refit=joint: k1 by the plumb-line estimate from the data set's long straight segments "
    "(<name>.NNN.lines) in its images, held in the refit and written to sequence.yaml; not with --vgg_k1.");
DEFINE_bool(
    vgg_warp_to_shared_k, sfm::VggImportOptions().warp_to_shared_k,
    "vgg: resample each image to the sequence's one K (H_i = K K_i^-1, cropped to the rectangle all frames "
    "cover) and keep each P's own pose, exact for the warped images; writes image_warps.txt. "
    "--vgg_refit_poses is then not used.");
DEFINE_string(
    odometry, "",
    "euroc: the robot's odometry file, world_T_base (TUM, or ASL CSV 'timestamp [ns],x,y,z,qw,qx,qy,qz'); "
    "required, since ASL folders hold none.");
DEFINE_string(calibration, "",
              "euroc, bags: the camera calibration instead of cam0/sensor.yaml (bags: of the CameraInfo topic "
              "and /tf_static): a Kalibr camchain (cam0), a ROS camera_info YAML, an EuRoC sensor.yaml or an "
              "OpenCV YAML as sequence.yaml.");
DEFINE_string(
    base_T_body, "",
    "euroc, bags: 'tx ty tz qx qy qz qw', the pose of the calibration's reference frame (Kalibr: the IMU; "
    "EuRoC: the body B; camera_info: the camera itself) in the robot base frame; empty: the identity.");
DEFINE_string(tum_camera, "fr1", "tum: which Kinect's published calibration to use: fr1, fr2 or fr3.");
DEFINE_int32(tum_stride, sfm::TumImportOptions().stride, "tum: keep every N-th image that has ground truth.");
DEFINE_double(tum_max_groundtruth_gap, sfm::TumImportOptions().max_groundtruth_gap,
              "tum: skip images between ground-truth poses more than this many seconds apart.");
DEFINE_string(image_topic, "",
              "bags: sensor_msgs/msg/Image or CompressedImage topic; empty: the bag's only one.");
DEFINE_string(
    odometry_topic, "",
    "bags: nav_msgs/msg/Odometry (or geometry_msgs/msg/PoseStamped, TransformStamped) topic of the "
    "robot base; empty: the bag's only one.");
DEFINE_string(
    camera_info_topic, "",
    "bags: sensor_msgs/msg/CameraInfo topic; empty: the bag's only one, or the one beside the image "
    "topic.");
DEFINE_string(groundtruth_topic, "",
              "bags: pose topic of the base's true poses (groundtruth.txt); empty: none.");
DEFINE_string(base_frame, "",
              "bags: robot base frame for T_base_camera; empty: the odometry's child_frame_id.");
DEFINE_string(camera_frame, "", "bags: camera frame for T_base_camera; empty: the images' frame_id.");
DEFINE_int32(every, 1, "bags: keep every N-th image.");
DEFINE_double(min_motion, 0,
              "bags: keyframes: keep an image only when the odometry moved at least this many metres (or "
              "turned --min_rotation) since the last kept one; 0 and 0: keep all.");
DEFINE_double(min_rotation, 0,
              "bags: keyframes: the rotation, radians, that also keeps an image (see --min_motion).");
DEFINE_double(start_time, 0, "bags: first image kept, seconds after the image topic's first stamp.");
DEFINE_double(end_time, std::numeric_limits<double>::infinity(),
              "bags: last image kept, seconds after the image topic's first stamp.");
DEFINE_double(
    max_odometry_gap, sfm::BagImportOptions().max_odometry_gap,
    "bags: seconds; images further than this from odometry samples are skipped, and odometry that "
    "starts or stops this much beyond the images is an error.");
DEFINE_string(
    odometry_noise, "",
    "bags: 'translation_sigma,rotation_sigma' written to sequence.yaml (SPEC's odometry noise keys); "
    "empty: left out, the pipeline's defaults.");

namespace {

sfm::Status ImportBag() {
  sfm::BagImportOptions options;
  options.image_topic = FLAGS_image_topic;
  options.odometry_topic = FLAGS_odometry_topic;
  options.camera_info_topic = FLAGS_camera_info_topic;
  options.groundtruth_topic = FLAGS_groundtruth_topic;
  options.base_frame = FLAGS_base_frame;
  options.camera_frame = FLAGS_camera_frame;
  options.every = FLAGS_every;
  options.min_motion = FLAGS_min_motion;
  options.min_rotation = FLAGS_min_rotation;
  options.start_time = FLAGS_start_time;
  options.end_time = FLAGS_end_time;
  options.max_odometry_gap = FLAGS_max_odometry_gap;
  options.scale.scale = FLAGS_scale;
  options.scale.max_width = FLAGS_max_width;
  options.overwrite = FLAGS_overwrite;
  if (!FLAGS_calibration.empty()) {
    sfm::Pose3 base_T_body;
    SFM_RETURN_IF_ERROR(sfm::ParsePoseText(FLAGS_base_T_body, "--base_T_body", &base_T_body));
    sfm::Calibration calibration;
    SFM_RETURN_IF_ERROR(sfm::ReadCalibrationFile(FLAGS_calibration, base_T_body, &calibration));
    options.calibration = calibration;
  }
  if (!FLAGS_odometry_noise.empty()) {
    sfm::OdometryNoise noise;
    char extra = 0;
    if (std::sscanf(FLAGS_odometry_noise.c_str(), "%lf,%lf%c", &noise.translation_sigma,
                    &noise.rotation_sigma, &extra) != 2 ||
        !(noise.translation_sigma > 0) || !(noise.rotation_sigma > 0)) {
      return sfm::Status::Error(
          "--odometry_noise must be 'translation_sigma,rotation_sigma', two numbers > 0 (found '" +
          FLAGS_odometry_noise + "')");
    }
    options.odometry_noise = noise;
  }
  sfm::BagImportSummary summary;
  return FLAGS_format == "rosbag" ? sfm::ImportRosbag1(FLAGS_input, options, FLAGS_output, &summary)
                                  : sfm::ImportRosbag2(FLAGS_input, options, FLAGS_output, &summary);
}

sfm::Status ReadDataSet(sfm::ImportedSequence* sequence) {
  if (FLAGS_format == "vgg") {
    sfm::VggImportOptions options;
    options.refit_poses = FLAGS_vgg_refit_poses;
    options.refit = FLAGS_vgg_refit == "pnp" ? sfm::VggRefit::kPnpMedianK : sfm::VggRefit::kJoint;
    options.refit_focal = FLAGS_vgg_refit_focal;
    options.refit_principal_point = FLAGS_vgg_refit_principal_point;
    options.refit_radial_k1 = FLAGS_vgg_refit_k1;
    options.k1 = FLAGS_vgg_k1;
    options.k1_from_lines = FLAGS_vgg_k1_from_lines;
    options.warp_to_shared_k = FLAGS_vgg_warp_to_shared_k;
    sfm::VggImportSummary summary;
    return sfm::ReadVggSequence(FLAGS_input, options, sequence, &summary);
  }
  if (FLAGS_format == "strecha") return sfm::ReadStrechaSequence(FLAGS_input, sequence);
  sfm::TumImportOptions options;
  SFM_RETURN_IF_ERROR(sfm::ParseTumCamera(FLAGS_tum_camera, &options.camera));
  options.stride = FLAGS_tum_stride;
  options.max_groundtruth_gap = FLAGS_tum_max_groundtruth_gap;
  return sfm::ReadTumSequence(FLAGS_input, options, sequence);
}

}  // namespace

// --format euroc: a robot's recording with its own odometry, written as it is (no simulated noise).
int ImportEuroc() {
  sfm::EurocImportOptions options;
  options.odometry_path = FLAGS_odometry;
  options.calibration_path = FLAGS_calibration;
  sfm::RecordedSequence sequence;
  sfm::Status status = sfm::ParsePoseText(FLAGS_base_T_body, "--base_T_body", &options.base_T_body);
  if (status.ok()) status = sfm::ReadEurocSequence(FLAGS_input, options, &sequence);
  if (status.ok()) status = sfm::WriteRecordedSequence(sequence, FLAGS_output, FLAGS_overwrite);
  if (!status.ok()) {
    std::fprintf(stderr, "import_sequence: %s\n", status.message().c_str());
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "makes a SPEC sequence directory from a data set with ground-truth cameras, an EuRoC folder or a ROS 2 or "
      "ROS 1 bag.\n"
      "  import_sequence --format vgg|strecha|tum|euroc|rosbag2|rosbag --input <data set dir or bag> --output "
      "<sequence dir> [flags]");
  gflags::SetVersionString("0.1.0");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);

  if (argc > 1) {
    std::fprintf(stderr, "import_sequence: unexpected argument '%s' (flags are --name=value; see --help)\n", argv[1]);
    return 2;
  }
  if (FLAGS_format != "vgg" && FLAGS_format != "strecha" && FLAGS_format != "tum" &&
      FLAGS_format != "euroc" && FLAGS_format != "rosbag2" && FLAGS_format != "rosbag") {
    std::fprintf(stderr, "import_sequence: --format must be vgg, strecha, tum, euroc, rosbag2 or rosbag (found '%s')\n",
                 FLAGS_format.c_str());
    return 2;
  }
  if (FLAGS_vgg_k1 != 0 && FLAGS_vgg_k1_from_lines) {
    // --vgg_k1_from_lines is on by default: a given k1 replaces it, unless both were asked for.
    if (!gflags::GetCommandLineFlagInfoOrDie("vgg_k1_from_lines").is_default) {
      std::fprintf(stderr, "import_sequence: --vgg_k1 and --vgg_k1_from_lines: give one\n");
      return 2;
    }
    FLAGS_vgg_k1_from_lines = false;
  }
  if (FLAGS_vgg_refit != "joint" && FLAGS_vgg_refit != "pnp") {
    std::fprintf(stderr, "import_sequence: --vgg_refit must be joint or pnp (found '%s')\n",
                 FLAGS_vgg_refit.c_str());
    return 2;
  }
  if (FLAGS_input.empty() || FLAGS_output.empty()) {
    std::fprintf(stderr, "import_sequence: --input and --output must name directories\n");
    return 2;
  }
  if (FLAGS_format == "euroc") return ImportEuroc();
  if (FLAGS_format == "rosbag2" || FLAGS_format == "rosbag") {
    const sfm::Status status = ImportBag();
    if (!status.ok()) {
      std::fprintf(stderr, "import_sequence: %s\n", status.message().c_str());
      return 1;
    }
    return 0;
  }
  sfm::SequenceWriteOptions options;
  options.scale.scale = FLAGS_scale;
  options.scale.max_width = FLAGS_max_width;
  options.odometry.scale_error = FLAGS_odometry_scale_error;
  options.odometry.distance_sigma = FLAGS_odometry_distance_sigma;
  options.odometry.rotation_sigma = FLAGS_odometry_rotation_sigma;
  options.odometry.rotation_bias = FLAGS_odometry_heading_bias;
  if (!(FLAGS_odometry_noise_scale >= 0 && std::isfinite(FLAGS_odometry_noise_scale))) {
    std::fprintf(stderr, "import_sequence: --odometry_noise_scale must be a finite number >= 0 (found %g)\n",
                 FLAGS_odometry_noise_scale);
    return 2;
  }
  options.odometry = options.odometry.Scaled(FLAGS_odometry_noise_scale);
  options.seed = FLAGS_seed;
  options.overwrite = FLAGS_overwrite;
  sfm::Status status = options.Check();
  if (!status.ok()) {
    std::fprintf(stderr, "import_sequence: %s\n", status.message().c_str());
    return 2;
  }

  sfm::ImportedSequence sequence;
  status = ReadDataSet(&sequence);
  if (status.ok()) status = sfm::WriteImportedSequence(sequence, options, FLAGS_output);
  if (!status.ok()) {
    std::fprintf(stderr, "import_sequence: %s\n", status.message().c_str());
    return 1;
  }
  return 0;
}
