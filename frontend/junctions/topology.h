// The topology graph of one image (paper section 4.2).
#pragma once

#include "frontend/junctions/junction.h"

namespace sfm {

// Links junctions that share a detected line segment (JunctionSegment::line_segment). Junctions
// are the graph's vertices by their index in `junctions`. Along one segment, each junction is
// linked to its neighbours in order along the line (a bar holding T's links them one after the
// other, not every pair), and each edge records the junction segment of either junction that
// points towards the other. With one junction at each end, as is usual, that is the paper's rule.
TopologyGraph BuildTopologyGraph(const Junctions& junctions);

}  // namespace sfm
