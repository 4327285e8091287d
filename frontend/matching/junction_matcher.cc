#include "frontend/matching/junction_matcher.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <utility>

#include "frontend/matching/depth_range.h"
#include "frontend/matching/junction_similarity.h"
#include "frontend/matching/similarity_table.h"
#include "frontend/matching/topology_similarity.h"

namespace sfm {

namespace {

// Rounds of the one-common-segment fixed point after the first partial pass (MatchJunctions).
constexpr int kOneCommonRounds = 4;

// The segment of `match`'s image-1 junction (num_a segments) paired with segment segment_b of its
// image-2 junction, or -1.
int PairedSegmentOfA(const JunctionMatch& match, int segment_b, int num_a, int num_b) {
  for (int s = 0; s < num_a; ++s) {
    if (PartnerSegment(match, s, num_a, num_b) == segment_b) return s;
  }
  return -1;
}

// Rivals on one arm (docs/matching.md): junctions p and q of one image (rivals for one partner)
// are two readings of one arm's end when they hold one detected line segment pointing the same
// way from both (one lies on the other's arm, or on its line beyond the end: a corner beyond a
// taken end-point and the junction holding that end, docs/junctions.md step 3), and both
// candidates pair that arm with the same segment of the partner (partner_of_p / partner_of_q map a
// segment of p / q to the partner's segment, -1 for none).
template <typename PartnerOfP, typename PartnerOfQ>
bool OneArm(const Junction& p, const Junction& q, const PartnerOfP& partner_of_p,
            const PartnerOfQ& partner_of_q) {
  for (int sp = 0; sp < p.NumSegments(); ++sp) {
    if (p.segments[sp].line_segment < 0) continue;
    for (int sq = 0; sq < q.NumSegments(); ++sq) {
      if (q.segments[sq].line_segment != p.segments[sp].line_segment) continue;
      if (p.SegmentDirection(sp).dot(q.SegmentDirection(sq)) <= 0) continue;
      const int partner = partner_of_p(sp);
      if (partner >= 0 && partner == partner_of_q(sq)) return true;
    }
  }
  return false;
}

AlliedRivals RivalsOnOneArm(const Junctions& a, const Junctions& b) {
  return [&a, &b](const JunctionMatch& x, const JunctionMatch& y) {
    // shift -1: an equal-count competitor of the partial pass, with no pairing; it stays a rival.
    if (x.shift < 0 || y.shift < 0) return false;
    if (x.index_b == y.index_b && x.index_a != y.index_a) {
      const Junction& p = a[x.index_a];
      const Junction& q = a[y.index_a];
      const int n_b = b[x.index_b].NumSegments();
      return OneArm(
          p, q, [&](int s) { return PartnerSegment(x, s, p.NumSegments(), n_b); },
          [&](int s) { return PartnerSegment(y, s, q.NumSegments(), n_b); });
    }
    if (x.index_a == y.index_a && x.index_b != y.index_b) {
      const Junction& p = b[x.index_b];
      const Junction& q = b[y.index_b];
      const int n_a = a[x.index_a].NumSegments();
      return OneArm(
          p, q, [&](int s) { return PairedSegmentOfA(x, s, n_a, p.NumSegments()); },
          [&](int s) { return PairedSegmentOfA(y, s, n_a, q.NumSegments()); });
    }
    return false;
  };
}

// The allied-rivals test rule (38) uses: RivalsOnOneArm.
AlliedRivals AlliedRivalsFor(const Junctions& a, const Junctions& b) { return RivalsOnOneArm(a, b); }

// depth_range (may be null): a pair it rejects is unmatched, for rule (38) and for sigma's
// topology support alike.
std::vector<JunctionMatch> Match(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                 const TopologyGraph& graph_b, const JunctionSimilarity& similarity,
                                 const MatchingOptions& options,
                                 const LocalDepthRange* depth_range = nullptr) {
  const int num_a = static_cast<int>(a.size());
  const int num_b = static_cast<int>(b.size());
  SimilarityTable table(num_a, num_b, [&similarity, &b, depth_range](int i, int j) {
    if (depth_range != nullptr && !depth_range->Passes(i, b[j].location)) return PairSimilarity();
    return similarity.Rho(i, j);
  });
  std::optional<TopologySimilarity> topology;
  if (options.use_topology) topology.emplace(a, graph_a, b, graph_b, &table);

  // Step 1 of section 4.4: the candidate list S. sigma = rho = 0 where rho is (C is empty then).
  std::vector<JunctionMatch> candidates;
  std::vector<int> partners;
  for (int i = 0; i < num_a; ++i) {
    partners.clear();
    similarity.PossiblePartners(i, &partners);  // the others have rho unmatched
    for (const int j : partners) {
      const PairSimilarity& rho = table.Get(i, j);
      if (!rho.Matched()) continue;
      const double similarity_ij = topology ? topology->Sigma(i, j) : rho.rho;
      if (similarity_ij > options.tau1) candidates.push_back({i, j, similarity_ij, rho.shift});
    }
  }
  // Step 2: the mutual test of (38).
  return SelectMatches(candidates, num_a, num_b, options.tau1, options.tau2, AlliedRivalsFor(a, b));
}

// True when segment segment_a of junction i (image 1) has a topology edge to a junction that
// `full` matches (match_of_a: index into full, or -1), and segment segment_b of junction j
// (image 2) an edge to that junction's partner, arriving through the segment the match pairs with
// the far end of the edge in image 1: the one common segment is seen as one edge in both frames.
bool SharedSegmentSupported(int i, int segment_a, int j, int segment_b, const Junctions& a,
                            const TopologyGraph& graph_a, const Junctions& b, const TopologyGraph& graph_b,
                            const std::vector<JunctionMatch>& full, const std::vector<int>& match_of_a) {
  for (const int edge_a : graph_a.edges_of_junction[i]) {
    const TopologyEdge& ea = graph_a.edges[edge_a];
    if (ea.junction_a == ea.junction_b) continue;
    const bool a_first = ea.junction_a == i;
    if ((a_first ? ea.segment_a : ea.segment_b) != segment_a) continue;
    const int far_a = a_first ? ea.junction_b : ea.junction_a;
    if (match_of_a[far_a] < 0) continue;
    const JunctionMatch& far = full[match_of_a[far_a]];
    const int far_segment_b = PartnerSegment(far, a_first ? ea.segment_b : ea.segment_a,
                                             a[far_a].NumSegments(), b[far.index_b].NumSegments());
    if (far_segment_b < 0) continue;
    for (const int edge_b : graph_b.edges_of_junction[j]) {
      const TopologyEdge& eb = graph_b.edges[edge_b];
      if (eb.junction_a == eb.junction_b) continue;
      const bool b_first = eb.junction_a == j;
      if ((b_first ? eb.segment_a : eb.segment_b) == segment_b &&
          (b_first ? eb.junction_b : eb.junction_a) == far.index_b &&
          (b_first ? eb.segment_b : eb.segment_a) == far_segment_b) {
        return true;
      }
    }
  }
  return false;
}

// A partial pass candidate pairing two junctions of equal segment counts with a segment missing:
// two L's sharing one segment (OneCommonRho), a candidate only while SharedSegmentSupported holds.
bool OneCommon(const JunctionMatch& match, const Junctions& a, const Junctions& b) {
  return match.Partial() && a[match.index_a].NumSegments() == b[match.index_b].NumSegments();
}

// Partial correspondence among the junctions `full` left unmatched (docs/matching.md, "Partial
// correspondence"): candidates are the leftover pairs with segment counts k and k + 1
// (PartialRho) and, as their competitors, the leftover pairs with equal counts (Rho: each lost the
// full pass's rule (38) or had no admissible shift, so it stays out of the result, but a junction
// with an equal-count rival as close as its partial partner is ambiguous). Rule (38) both ways on
// rho (topology's sigma needs equal counts at both ends of an edge). depth_range (may be null): as
// in the full pass, a pair it rejects is no candidate, partial or competitor (an occlusion T read
// as a Y or an L against a real L elsewhere on the epipolar line is a partner at another depth than
// the verified matches around it). In the order of a's junctions and of their partners: the scan
// of every round of GuidedPass's fixed point, computed once (its tests depend on `full` only).
std::vector<JunctionMatch> PartialCandidates(const Junctions& a, const Junctions& b,
                                             const JunctionSimilarity& similarity,
                                             const std::vector<JunctionMatch>& full,
                                             const MatchingOptions& options,
                                             const LocalDepthRange* depth_range) {
  std::vector<char> matched_a(a.size(), 0), matched_b(b.size(), 0);
  for (const JunctionMatch& match : full) {
    matched_a[match.index_a] = 1;
    matched_b[match.index_b] = 1;
  }
  std::vector<JunctionMatch> candidates;
  std::vector<int> partners;
  for (int i = 0; i < static_cast<int>(a.size()); ++i) {
    if (matched_a[i]) continue;
    const int n_a = a[i].NumSegments();
    // The cheap epipolar scan first (one product over b's locations): most leftover pairs are far
    // apart, and testing each with Rho or PartialRho cost more than the rest of the partial pass.
    partners.clear();
    similarity.PossiblePartners(i, &partners, 1);
    for (const int j : partners) {
      if (matched_b[j]) continue;
      const int n_b = b[j].NumSegments();
      // The depth test after rho: the range of junction i is computed on its first use, and most
      // leftover pairs fail rho's band test first.
      auto passes_depth = [&](const PairSimilarity& rho) {
        return rho.Matched() && rho.rho > options.tau1 &&
               (depth_range == nullptr || depth_range->Passes(i, b[j].location));
      };
      if (n_a == n_b) {
        const PairSimilarity rho = similarity.Rho(i, j);
        // missing_a = missing_b = -1 and the flag below: a competitor only.
        if (passes_depth(rho)) {
          candidates.push_back({i, j, rho.rho, -1, -1, -1});
        } else if (!rho.Matched() && n_a == 2) {
          // Two L's with no admissible shift: perhaps two corners of one vertex sharing a segment.
          const PairSimilarity one = similarity.OneCommonRho(i, j);
          if (passes_depth(one))
            candidates.push_back({i, j, one.rho, one.shift, one.missing_a, one.missing_b});
        }
      } else if (std::abs(n_a - n_b) == 1) {
        const PairSimilarity rho = similarity.PartialRho(i, j);
        if (passes_depth(rho)) candidates.push_back({i, j, rho.rho, rho.shift, rho.missing_a, rho.missing_b});
      }
    }
  }
  return candidates;
}

// The partial matches rule (38) selects among `candidates` (PartialCandidates), a OneCommon pair
// taking part when `supporting` (the matches whose junctions may support it: `full` and, in the
// later rounds of GuidedPass's fixed point, the partial matches of the round before) shows its
// shared segment as one edge in both frames.
std::vector<JunctionMatch> MatchPartial(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                        const TopologyGraph& graph_b,
                                        const std::vector<JunctionMatch>& candidates,
                                        const std::vector<JunctionMatch>& supporting,
                                        const MatchingOptions& options) {
  std::vector<int> match_of_a(a.size(), -1);
  for (size_t m = 0; m < supporting.size(); ++m) match_of_a[supporting[m].index_a] = static_cast<int>(m);
  std::vector<JunctionMatch> taking_part;
  taking_part.reserve(candidates.size());
  for (const JunctionMatch& match : candidates) {
    if (OneCommon(match, a, b) &&
        !SharedSegmentSupported(match.index_a, 1 - match.missing_a, match.index_b, 1 - match.missing_b, a,
                                graph_a, b, graph_b, supporting, match_of_a)) {
      continue;
    }
    taking_part.push_back(match);
  }
  std::vector<JunctionMatch> partial;
  for (const JunctionMatch& match :
       SelectMatches(taking_part, static_cast<int>(a.size()), static_cast<int>(b.size()), options.tau1,
                     options.tau2, AlliedRivalsFor(a, b))) {
    if (match.Partial()) partial.push_back(match);
  }
  return partial;
}

// The locations of the matched junctions, x1[k] in a and x2[k] in b for matches[k].
void MatchLocations(const Junctions& a, const Junctions& b, const std::vector<JunctionMatch>& matches,
                    std::vector<Eigen::Vector2d>* x1, std::vector<Eigen::Vector2d>* x2) {
  x1->clear();
  x2->clear();
  x1->reserve(matches.size());
  x2->reserve(matches.size());
  for (const JunctionMatch& match : matches) {
    x1->push_back(a[match.index_a].location);
    x2->push_back(b[match.index_b].location);
  }
}

}  // namespace

std::vector<JunctionMatch> MatchJunctions(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                         const TopologyGraph& graph_b, const Eigen::Matrix3d& F,
                                         const MatchingOptions& options) {
  const Status status = options.Check();
  CHECK(status.ok()) << status.message();
  CHECK(F.allFinite()) << "F:\n" << F;
  return Match(a, graph_a, b, graph_b, JunctionSimilarity(a, b, F, options), options);
}

std::vector<JunctionMatch> VerifiedFirstPass(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                             const TopologyGraph& graph_b, const PairGeometry& geometry,
                                             const MatchingOptions& options, MatchingDiagnostics* diagnostics) {
  const Status status = options.Check();
  CHECK(status.ok()) << status.message();
  CHECK(geometry.K.allFinite() && geometry.covariance.allFinite() && geometry.camera2_T_camera1.translation.allFinite())
      << "PairGeometry not finite";
  CHECK(diagnostics != nullptr);
  MatchingDiagnostics& report = *diagnostics;
  report = MatchingDiagnostics();
  std::vector<JunctionMatch> first = Match(a, graph_a, b, graph_b, JunctionSimilarity(a, b, geometry, options), options);
  report.first_pass_matches = static_cast<int>(first.size());
  if (!options.refine_geometry) return first;

  // Verification: the pose the first pass's matches support, with the odometry as the prior.
  std::vector<Eigen::Vector2d> x1, x2;
  MatchLocations(a, b, first, &x1, &x2);
  report.refinement = RefinePairGeometry(geometry, x1, x2, RefinementSettings(options));
  return first;
}

std::vector<JunctionMatch> GuidedPass(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                      const TopologyGraph& graph_b, std::vector<JunctionMatch> first,
                                      const MatchingOptions& options, MatchingDiagnostics* diagnostics) {
  CHECK(diagnostics != nullptr);
  MatchingDiagnostics& report = *diagnostics;
  if (!options.refine_geometry || !report.refinement.Refined()) return first;
  std::vector<Eigen::Vector2d> x1, x2;
  MatchLocations(a, b, first, &x1, &x2);

  // The guided pass: every pair again, in the band of the refined pose. A first-pass match off the
  // refined epipolar geometry is no longer a candidate; a pair the wide band lost to a wrong
  // competitor can now win.
  MatchingOptions guided = options;
  guided.use_pose_band = true;
  guided.band_sigmas = options.refine_gate_sigmas;
  const JunctionSimilarity similarity(a, b, report.refinement.geometry, guided);
  std::optional<LocalDepthRange> depth_range;
  if (options.depth_range_neighbours > 0) {
    // The verified matches: the first pass's matches within the gate at the refined pose.
    std::vector<Eigen::Vector2d> x1_verified, x2_verified;
    std::vector<int> source_a;
    for (size_t k = 0; k < first.size(); ++k) {
      if (!report.refinement.inlier[k]) continue;
      x1_verified.push_back(x1[k]);
      x2_verified.push_back(x2[k]);
      source_a.push_back(first[k].index_a);
    }
    std::vector<Eigen::Vector2d> locations_a;
    locations_a.reserve(a.size());
    for (const Junction& junction : a) locations_a.push_back(junction.location);
    depth_range.emplace(report.refinement.geometry, x1_verified, x2_verified, source_a, locations_a,
                        options.depth_range_neighbours, options.refine_gate_sigmas,
                        options.location_sigma_px);
  }
  std::vector<JunctionMatch> matches =
      Match(a, graph_a, b, graph_b, similarity, guided, depth_range ? &*depth_range : nullptr);
  // Only here: in the refined band (about 1.8 px) a partial pair has few rivals; in the odometry's
  // band the weaker, k/(k+1)-scaled support would compete with many wrong full-count partners.
  const std::vector<JunctionMatch> partial_candidates =
      PartialCandidates(a, b, similarity, matches, guided, depth_range ? &*depth_range : nullptr);
  std::vector<JunctionMatch> partial =
      MatchPartial(a, graph_a, b, graph_b, partial_candidates, matches, guided);
  // One common segment: a pair's support may also be a partial match (a chain of corners along one
  // edge); again with the full and partial matches of the round before as neighbours, until the
  // partial matches stop changing (a few rounds; capped, as a selection by (38) need not be monotone).
  for (int round = 0; round < kOneCommonRounds; ++round) {
    std::vector<JunctionMatch> supporting = matches;
    supporting.insert(supporting.end(), partial.begin(), partial.end());
    std::vector<JunctionMatch> next =
        MatchPartial(a, graph_a, b, graph_b, partial_candidates, supporting, guided);
    const bool same =
        next.size() == partial.size() && std::equal(next.begin(), next.end(), partial.begin(),
                                                    [](const JunctionMatch& x, const JunctionMatch& y) {
                                                      return x.index_a == y.index_a && x.index_b == y.index_b;
                                                    });
    partial = std::move(next);
    if (same) break;
  }
  report.partial_matches = static_cast<int>(partial.size());
  matches.insert(matches.end(), partial.begin(), partial.end());
  std::stable_sort(matches.begin(), matches.end(),
                   [](const JunctionMatch& x, const JunctionMatch& y) { return x.index_a < y.index_a; });
  return matches;
}

std::vector<JunctionMatch> MatchJunctions(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                         const TopologyGraph& graph_b, const PairGeometry& geometry,
                                         const MatchingOptions& options, MatchingDiagnostics* diagnostics) {
  MatchingDiagnostics local;
  MatchingDiagnostics* report = diagnostics ? diagnostics : &local;
  return GuidedPass(a, graph_a, b, graph_b, VerifiedFirstPass(a, graph_a, b, graph_b, geometry, options, report),
                    options, report);
}

namespace {

// Whether the median of `distances` (pixels) lies beyond kDisagreementBands guided bands,
// refine_gate_sigmas * location_sigma_px; true when there is none.
bool MedianBeyondBands(std::vector<double> distances, const MatchingOptions& options) {
  if (distances.empty()) return true;
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return distances[distances.size() / 2] >
         kDisagreementBands * options.refine_gate_sigmas * options.location_sigma_px;
}

}  // namespace

bool HypothesisDisputed(const Pose3& hypothesis, const PairRefinement& verified, const std::vector<Eigen::Vector2d>& x1,
                        const std::vector<Eigen::Vector2d>& x2, const MatchingOptions& options) {
  if (!verified.Refined()) return true;
  CHECK_EQ(x1.size(), x2.size());
  CHECK_EQ(verified.inlier.size(), x1.size());
  const Pose3& camera2_T_camera1 = verified.geometry.camera2_T_camera1;
  // The scale, which two images cannot tell, taken from the verified pose.
  Pose3 at_scale = hypothesis;
  const double norm = hypothesis.translation.norm();
  if (norm > 0) at_scale.translation *= camera2_T_camera1.translation.norm() / norm;
  const Eigen::Matrix3d& K = verified.geometry.K;
  const Eigen::Matrix3d K_inverse = K.inverse();
  std::vector<double> distances;
  for (size_t k = 0; k < x1.size(); ++k) {
    if (!verified.inlier[k]) continue;
    // The depth as the guided pass's depth range reads it: x2's parallax along the epipolar line.
    const ParallaxFrame frame = ParallaxFrameOf(verified.geometry, x1[k]);
    if (!frame.tested) continue;
    const double inverse_depth =
        InverseDepthOfParallax(frame, camera2_T_camera1.translation.z(), (x2[k] - frame.v).dot(frame.direction));
    if (!(inverse_depth > 0 && std::isfinite(inverse_depth))) continue;
    const Eigen::Vector3d in_camera2 = at_scale * (K_inverse * x1[k].homogeneous() / inverse_depth);
    distances.push_back(in_camera2.z() > 0 ? ((K * in_camera2).hnormalized() - x2[k]).norm()
                                           : std::numeric_limits<double>::infinity());
  }
  return MedianBeyondBands(std::move(distances), options);
}

bool MatchesDisagree(const Junctions& a, const Junctions& b, const std::vector<JunctionMatch>& matches,
                     const PairGeometry& geometry, const MatchingOptions& options) {
  if (matches.empty()) return false;
  // The median |Sampson distance| of the matches under `geometry`'s pose.
  const Eigen::Matrix3d F = geometry.Fundamental();
  std::vector<double> distances;
  for (const JunctionMatch& match : matches) {
    distances.push_back(std::abs(SampsonDistance(F, a[match.index_a].location, b[match.index_b].location)));
  }
  return MedianBeyondBands(std::move(distances), options);
}

std::vector<JunctionMatch> GuidedPassOrHypotheses(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                                  const TopologyGraph& graph_b, std::vector<JunctionMatch> first,
                                                  const PairGeometry& geometry,
                                                  const std::vector<Pose3>& hypotheses,
                                                  const MatchingOptions& options, MatchingDiagnostics* diagnostics) {
  std::vector<char> disputed;
  if (options.refine_geometry && !hypotheses.empty()) {
    std::vector<Eigen::Vector2d> x1, x2;
    MatchLocations(a, b, first, &x1, &x2);
    for (const Pose3& hypothesis : hypotheses) {
      disputed.push_back(HypothesisDisputed(hypothesis, diagnostics->refinement, x1, x2, options));
    }
  }
  std::vector<JunctionMatch> matches = GuidedPass(a, graph_a, b, graph_b, std::move(first), options, diagnostics);
  for (size_t h = 0; h < disputed.size(); ++h) {
    if (!disputed[h]) continue;
    PairGeometry centred = geometry;
    centred.camera2_T_camera1 = hypotheses[h];
    MatchingDiagnostics other;
    std::vector<JunctionMatch> other_matches = GuidedPass(
        a, graph_a, b, graph_b, VerifiedFirstPass(a, graph_a, b, graph_b, centred, options, &other), options, &other);
    VLOG(1) << "pose hypothesis " << h << ": " << matches.size() << " matches so far, " << other_matches.size()
            << " centred on it";
    const double n = static_cast<double>(matches.size()), other_n = static_cast<double>(other_matches.size());
    if (!other.refinement.Refined() || other_n < kHypothesisMatchRatio * n ||
        other_n < n + kHypothesisExcessSigmas * std::sqrt(n)) {
      continue;
    }
    std::vector<Eigen::Vector2d> x1, x2;
    MatchLocations(a, b, other_matches, &x1, &x2);
    PairRefinement refinement = RefinePairGeometry(geometry, x1, x2, RefinementSettings(options));
    if (!refinement.Refined()) continue;
    *diagnostics = std::move(other);
    diagnostics->refinement = std::move(refinement);
    diagnostics->recentred = true;
    matches = std::move(other_matches);
  }
  return matches;
}

PairRefinementSettings RefinementSettings(const MatchingOptions& options) {
  PairRefinementSettings settings;
  settings.location_sigma_px = options.location_sigma_px;
  settings.gate_sigmas = options.refine_gate_sigmas;
  settings.min_inliers = options.refine_min_inliers;
  return settings;
}

}  // namespace sfm
