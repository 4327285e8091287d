#include "sfm_app/flags/detector_flags.h"

DEFINE_string(segments, "fast",
              "Line segment detector: 'fast' (anchored edge chaining) or 'reference' "
              "(the paper's edge filter + Hough transform + sub-pixel fit).");

namespace sfm {

bool SegmentMethodFromFlags(SegmentDetectorOptions* options, std::string* error) {
  if (FLAGS_segments == "fast") {
    options->method = SegmentMethod::kFast;
  } else if (FLAGS_segments == "reference") {
    options->method = SegmentMethod::kReference;
  } else {
    *error = "--segments must be 'fast' or 'reference', not '" + FLAGS_segments + "'";
    return false;
  }
  return true;
}

}  // namespace sfm
