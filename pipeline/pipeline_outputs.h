// Writing the output directory of SPEC section 3 from a run's result.
#pragma once

#include <string>
#include <vector>

#include "frontend/sequence/sequence.h"
#include "util/status.h"
#include "pipeline/pipeline_result.h"

namespace sfm {

// The run's log (glog INFO and WARNING lines), written into the output directory by junction_sfm.
inline constexpr char kLogFileName[] = "junction_sfm.log";

// The names a run writes at the top of its output directory (SPEC section 3, report.html and the
// log): OutputDirectory replaces an existing directory only when it holds nothing else.
std::vector<std::string> OutputEntryNames();

// Every name the writers will write, checked before the work starts (a failure after the work
// would waste it): the image paths as COLMAP's images.txt holds them (no white space) and as the
// junction JSON holds them (valid UTF-8). One line naming images.txt's line.
Status CheckOutputNames(const Sequence& sequence);

// Writes every output the result has: junctions/, matches/, tracks.csv, the trajectories,
// wireframe.ply, colmap/ and metrics.json. Each file atomically; the directory must exist.
Status WriteOutputs(const Sequence& sequence, const PipelineResult& result, const std::string& output_dir);

// metrics.json: the SPEC keys (null where a figure does not apply) and a few of the project's own.
std::string MetricsJson(const Sequence& sequence, const PipelineResult& result);

}  // namespace sfm
