// matches/<NNNNNN>_<MMMMMM>.csv of the output directory (SPEC section 3).
#pragma once

#include <string>
#include <vector>

#include "frontend/junctions/junction.h"
#include "frontend/matching/junction_matcher.h"

namespace sfm {

// The header `id_a,id_b,similarity`, then one row per match: the junctions' `id`s (as in
// junctions/*.json), not their indices, and the similarity in shortest exact form.
std::string MatchesCsv(const Junctions& a, const Junctions& b, const std::vector<JunctionMatch>& matches);

}  // namespace sfm
