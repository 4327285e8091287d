// tracks.csv of the output directory (SPEC section 3).
#pragma once

#include <string>
#include <vector>

#include "frontend/junctions/junction.h"
#include "frontend/tracks/tracks.h"

namespace sfm {

// The text of tracks.csv: the header `track_id,frame,junction_id`, then one row per view, tracks in
// order, views in increasing frame; junction_id is the junction's `id` (as in junctions/*.json),
// not its index. Lines end with "\n". The views must index frames (CHECKed).
std::string TracksCsv(const std::vector<JunctionTrack>& tracks, const std::vector<Junctions>& frames);

}  // namespace sfm
