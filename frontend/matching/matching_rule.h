// The matching rule (38) of paper section 4.4, applied both ways.
#pragma once

#include <functional>
#include <vector>

namespace sfm {

// A matched (or candidate) pair: junction index_a of image 1 and index_b of image 2; segment i of
// the first corresponds to segment (i + shift) mod N of the second (eq. 32-33).
//
// A partial match (not in the paper; docs/matching.md, "Partial correspondence") pairs a junction
// of k segments with one of k + 1: missing_a (or missing_b) is the segment of the larger junction
// left without a partner, and shift applies to the larger junction's segments with that one removed
// (cyclic order kept), renumbered 0..k-1. PartnerSegment does the bookkeeping. Both are -1 for a
// full match.
struct JunctionMatch {
  int index_a = -1;
  int index_b = -1;
  double similarity = 0;  // sigma (section 4.2) or rho (34), as MatchingOptions::use_topology says
  int shift = 0;
  int missing_a = -1;
  int missing_b = -1;
  bool Partial() const { return missing_a >= 0 || missing_b >= 0; }
};

// The segment of junction index_b (num_b segments) that segment segment_a of junction index_a
// (num_a segments) corresponds to under `match`, or -1 when segment_a is the partial match's
// missing_a.
int PartnerSegment(const JunctionMatch& match, int segment_a, int num_a, int num_b);

// Eq. (38) both ways. Candidates are those with similarity > tau1; a candidate (J, J') is kept when
// it has the largest similarity among J's candidates and beats each other one by more than tau2,
// and the same among J''s candidates. At most one candidate per pair; O(candidates).
//
// allied (may be empty): called with two candidates that share one junction (both index_a or both
// index_b); true when the other two junctions are two readings of one arm's end (docs/matching.md,
// "Rivals on one arm"), which then do not count against each other in the margin: the larger
// still has to beat every other candidate by more than tau2.
using AlliedRivals = std::function<bool(const JunctionMatch&, const JunctionMatch&)>;
std::vector<JunctionMatch> SelectMatches(const std::vector<JunctionMatch>& candidates, int num_a, int num_b,
                                         double tau1, double tau2,
                                         const AlliedRivals& allied = AlliedRivals());

}  // namespace sfm
