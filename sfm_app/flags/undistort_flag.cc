#include "sfm_app/flags/detector_flags.h"

DEFINE_string(
    undistort_interpolation, sfm::UndistortInterpolationName(sfm::kDetectionInterpolation),
    "Resampling of each frame to the undistorted image when the camera has lens distortion: 'linear', "
    "'cubic' or 'lanczos4' (docs/decisions.md).");

DEFINE_bool(undistort_full_view, sfm::kDetectionView == sfm::UndistortView::kFullView,
            "With lens distortion: detect on a canvas holding the stored image's whole field of view (same "
            "focal lengths, principal point shifted), so junctions may lie outside the image in K's pixels "
            "(docs/decisions.md).");

namespace sfm {

UndistortView UndistortViewFromFlags() {
  return FLAGS_undistort_full_view ? UndistortView::kFullView : UndistortView::kSameSize;
}

bool UndistortInterpolationFromFlags(UndistortInterpolation* interpolation, std::string* error) {
  if (ParseUndistortInterpolation(FLAGS_undistort_interpolation, interpolation)) return true;
  *error = "--undistort_interpolation must be 'linear', 'cubic' or 'lanczos4', not '" +
           FLAGS_undistort_interpolation + "'";
  return false;
}

}  // namespace sfm
