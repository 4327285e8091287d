#include "sfm_app/flags/detector_flags.h"

DEFINE_string(segments, sfm::ToString(sfm::SegmentDetectorOptions().method),
              "Line segment detector: 'fast' (anchored edge chaining) or 'reference' "
              "(the paper's edge filter + Hough transform + sub-pixel fit).");

namespace sfm {

bool SegmentMethodFromFlags(SegmentDetectorOptions* options, std::string* error) {
  const Status status = FromString(FLAGS_segments, &options->method);
  if (!status.ok()) *error = "--segments: " + status.message();
  return status.ok();
}

}  // namespace sfm
