// Side-by-side picture of junction matches in the style of Shen & Palmer's Fig. 6 (match_junctions).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "frontend/junctions/junction.h"
#include "frontend/matching/matching_rule.h"

namespace sfm {

// Image 1 left, image 2 right (8-bit grey or BGR, shown dimmed in grey), each enlarged `scale`
// times. Unmatched junctions are drawn thin in grey. Each match is numbered 1, 2, ... (in the order
// given) beside its junction in both images; segment i of its junction in image 1 and its partner
// segment (PartnerSegment: (i + shift) mod N for a full match) are drawn in the same colour (colours
// cycle over the segments and from one match to the next, so neighbouring matches differ); a
// partial match's left-out segment is drawn thin in grey. `correct`, if not empty, gives
// a verdict per match: wrong ones get their number in red on a white box.
cv::Mat DrawMatchOverlay(const cv::Mat& image_a, const Junctions& a, const cv::Mat& image_b, const Junctions& b,
                         const std::vector<JunctionMatch>& matches, int scale,
                         const std::vector<bool>& correct = {});

}  // namespace sfm
