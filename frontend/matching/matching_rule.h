// The matching rule (38) of paper section 4.4, applied both ways.
#pragma once

#include <vector>

namespace sfm {

// A matched (or candidate) pair: junction index_a of image 1 and index_b of image 2; segment i of
// the first corresponds to segment (i + shift) mod N of the second (eq. 32-33).
struct JunctionMatch {
  int index_a = -1;
  int index_b = -1;
  double similarity = 0;  // sigma (section 4.2) or rho (34), as MatchingOptions::use_topology says
  int shift = 0;
};

// Eq. (38) both ways. Candidates are those with similarity > tau1; a candidate (J, J') is kept when
// it has the largest similarity among J's candidates and beats each other one by more than tau2,
// and the same among J''s candidates. At most one candidate per pair; O(candidates).
std::vector<JunctionMatch> SelectMatches(const std::vector<JunctionMatch>& candidates, int num_a, int num_b,
                                         double tau1, double tau2);

}  // namespace sfm
