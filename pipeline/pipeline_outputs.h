// Writing the output directory of SPEC section 3 from a run's result.
#pragma once

#include <string>

#include "frontend/sequence/sequence.h"
#include "util/status.h"
#include "pipeline/pipeline_result.h"

namespace sfm {

// Writes every output the result has: junctions/, matches/, tracks.csv, the trajectories,
// wireframe.ply, colmap/ and metrics.json. Each file atomically; the directory must exist.
Status WriteOutputs(const Sequence& sequence, const PipelineResult& result, const std::string& output_dir);

// metrics.json: the SPEC keys (null where a figure does not apply) and a few of the project's own.
std::string MetricsJson(const Sequence& sequence, const PipelineResult& result);

}  // namespace sfm
