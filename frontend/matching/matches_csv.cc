#include "frontend/matching/matches_csv.h"

#include "util/number_text.h"

namespace sfm {

std::string MatchesCsv(const Junctions& a, const Junctions& b, const std::vector<JunctionMatch>& matches) {
  std::string csv = "id_a,id_b,similarity\n";
  for (const JunctionMatch& match : matches) {
    csv += std::to_string(a[match.index_a].id) + "," + std::to_string(b[match.index_b].id) + "," +
           ShortestNumberText(match.similarity) + "\n";
  }
  return csv;
}

}  // namespace sfm
