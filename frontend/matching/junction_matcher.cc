#include "frontend/matching/junction_matcher.h"

#include <optional>

#include <glog/logging.h>

#include "frontend/matching/junction_similarity.h"
#include "frontend/matching/similarity_table.h"
#include "frontend/matching/topology_similarity.h"

namespace sfm {

namespace {

std::vector<JunctionMatch> Match(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                 const TopologyGraph& graph_b, const JunctionSimilarity& similarity,
                                 const MatchingOptions& options) {
  const int num_a = static_cast<int>(a.size());
  const int num_b = static_cast<int>(b.size());
  SimilarityTable table(num_a, num_b, [&similarity](int i, int j) { return similarity.Rho(i, j); });
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
  return SelectMatches(candidates, num_a, num_b, options.tau1, options.tau2);
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

std::vector<JunctionMatch> MatchJunctions(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                         const TopologyGraph& graph_b, const PairGeometry& geometry,
                                         const MatchingOptions& options, MatchingDiagnostics* diagnostics) {
  const Status status = options.Check();
  CHECK(status.ok()) << status.message();
  CHECK(geometry.K.allFinite() && geometry.covariance.allFinite() && geometry.camera2_T_camera1.translation.allFinite())
      << "PairGeometry not finite";
  MatchingDiagnostics local;
  MatchingDiagnostics& report = diagnostics ? *diagnostics : local;
  report = MatchingDiagnostics();
  std::vector<JunctionMatch> first = Match(a, graph_a, b, graph_b, JunctionSimilarity(a, b, geometry, options), options);
  report.first_pass_matches = static_cast<int>(first.size());
  if (!options.refine_geometry) return first;

  // Verification: the pose the first pass's matches support, with the odometry as the prior.
  std::vector<Eigen::Vector2d> x1, x2;
  x1.reserve(first.size());
  x2.reserve(first.size());
  for (const JunctionMatch& match : first) {
    x1.push_back(a[match.index_a].location);
    x2.push_back(b[match.index_b].location);
  }
  PairRefinementSettings settings;
  settings.location_sigma_px = options.location_sigma_px;
  settings.gate_sigmas = options.refine_gate_sigmas;
  settings.min_inliers = options.refine_min_inliers;
  report.refinement = RefinePairGeometry(geometry, x1, x2, settings);
  if (!report.refinement.Refined()) return first;

  // The guided pass: every pair again, in the band of the refined pose. A first-pass match off the
  // refined epipolar geometry is no longer a candidate; a pair the wide band lost to a wrong
  // competitor can now win.
  MatchingOptions guided = options;
  guided.use_pose_band = true;
  guided.band_sigmas = options.refine_gate_sigmas;
  return Match(a, graph_a, b, graph_b, JunctionSimilarity(a, b, report.refinement.geometry, guided), guided);
}

}  // namespace sfm
