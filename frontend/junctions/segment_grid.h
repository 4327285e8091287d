// Candidate pairs for the junction test, found through a uniform grid instead of all n^2 pairs.
#pragma once

#include <utility>
#include <vector>

#include "frontend/junctions/intersection.h"

namespace sfm {

// Pairs (i, j), i < j, of segments whose bodies, each extended by `reach` pixels past both
// end-points and thickened by `pad` pixels on every side, pass through a common grid cell.
// Every pair whose junction moves no end-point by more than `reach` is among them: their junction
// point lies on both extended bodies, hence in a cell both pass through; pad covers two pieces of
// one line that are offset sideways by up to pad. Segments with use[i] false are left out.
// Each pair is listed once, in an order fixed by the input.
std::vector<std::pair<int, int>> CandidatePairs(const std::vector<SegmentLine>& lines,
                                                const std::vector<bool>& use, double reach, double pad);

}  // namespace sfm
