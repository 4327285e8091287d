#include "sfm_app/flags/detector_flags.h"

DEFINE_string(
    undistort_interpolation, sfm::UndistortInterpolationName(sfm::kDetectionInterpolation),
    "Resampling of each frame to the undistorted image when the camera has lens distortion: 'linear', "
    "'cubic' or 'lanczos4' (docs/junction_results.md, \"Session 7: lens distortion\").");

namespace sfm {

bool UndistortInterpolationFromFlags(UndistortInterpolation* interpolation, std::string* error) {
  if (ParseUndistortInterpolation(FLAGS_undistort_interpolation, interpolation)) return true;
  *error = "--undistort_interpolation must be 'linear', 'cubic' or 'lanczos4', not '" +
           FLAGS_undistort_interpolation + "'";
  return false;
}

}  // namespace sfm
