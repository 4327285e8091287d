// Similarity of two junctions under the epipolar constraint, rho(J, J') (paper section 4.1, eq.
// 31-34), with the physical constraints of section 4.3 applied under each segment correspondence.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "frontend/junctions/junction.h"
#include "frontend/matching/epipolar_transfer.h"
#include "frontend/matching/matching_options.h"
#include "frontend/matching/pair_geometry.h"

namespace sfm {

// Eq. (31) (exponential, w such that exp(-w R) = 0.01) or its linear form (footnote 10), for the
// distances d, d' (pixels) of each junction location from the epipolar line of the other's. Both
// must be <= R (pixels).
double Rho1(double d, double d_prime, double R, Rho1Kind kind);

// rho of a pair and the shift k that maximised M(k) in (33): segment i of J corresponds to segment
// (i + shift) mod N of J'. shift = -1: the pair is unmatched (different segment counts, d or d' > R,
// or no shift passes (17), (36) and (37)), and rho = 0.
// For a partial pair (JunctionSimilarity::PartialRho), missing_a or missing_b is the larger
// junction's segment left out and shift applies to the renumbered subset (JunctionMatch).
struct PairSimilarity {
  double rho = 0;
  int shift = -1;
  int missing_a = -1;
  int missing_b = -1;
  bool Matched() const { return shift >= 0; }
};

// rho for the pairs of two junction sets, with everything that depends on one junction only (its
// segments, the epipolar lines of its location and end-points) computed once.
class JunctionSimilarity {
 public:
  // x2^T F x1 = 0 for x1 in the image of `a`, x2 in that of `b`.
  JunctionSimilarity(const Junctions& a, const Junctions& b, const Eigen::Matrix3d& F,
                     const MatchingOptions& options);
  // F = geometry.Fundamental(); each pair's band from the pose covariance instead of R, and the
  // cheirality test where options.use_cheirality (docs/matching.md, "Pose uncertainty").
  JunctionSimilarity(const Junctions& a, const Junctions& b, const PairGeometry& geometry,
                     const MatchingOptions& options);

  // Eq. (34): rho = 0.5 (rho1 + rho2), rho2 = max_k M(k) (33) over the shifts allowed.
  PairSimilarity Rho(int index_a, int index_b) const;

  // Partial correspondence (not in the paper; docs/matching.md, "Partial correspondence"): the
  // junctions have k >= 2 and k + 1 segments (either way round). Over every segment m of the larger
  // one left out and every shift k of the remaining segments (their cyclic order kept), (36), (37)
  // and (17) as for Rho, and M = (1/(k+1)) sum over the k pairings of H H': the left-out segment's
  // term is 0, so for equal per-segment support a partial M is k/(k+1) of a full one and never
  // outranks it. rho = 0.5 (rho1 + max M), rho1 and the band / cheirality tests as in Rho.
  // The left-out segment must be one detection can miss alone: (a) not half of a line through the
  // location (a T's bar, an X's lines: from one detected line segment, or opposite within
  // cyclic_order_min_angle_deg), and (b) the kept segments have as many such lines as the smaller
  // junction (a T without its stem is a straight line, not an L).
  // Unmatched (shift -1) for other segment counts or when no segment may be left out.
  PairSimilarity PartialRho(int index_a, int index_b) const;

  // Two L's sharing one segment (not in the paper; docs/matching.md, "One common segment"): two corners
  // of one 3-edge vertex, segments (1, 2) detected in one frame and (2, 3) in the other. Over every
  // pairing of one segment of a with one of b, (37) and (17) for that pair, and M = H H' / 3, the
  // mean over the three segments of the union with the two unshared ones' terms 0 (as PartialRho
  // counts a missing segment). rho = 0.5 (rho1 + max M). missing_a / missing_b: the unshared segment
  // of each, shift 0. Unmatched for other segment counts, outside the band or cheirality test, or
  // when no pairing passes (37) and (17). Alone this is weak evidence (one segment, no turn): the
  // matcher also asks for topology support through the shared segment (junction_matcher.cc).
  PairSimilarity OneCommonRho(int index_a, int index_b) const;

  // The junctions of b that Rho(index_a, .) does not reject by its first, cheap tests (same segment
  // count, p'0 within R or the largest band of index_a from the epipolar line of p0), appended to
  // `out` in increasing index. Every other pair has Rho unmatched: the candidate scan of (38) needs
  // Rho only for these. max_count_difference = 1: also the junctions with one segment more or less,
  // which PartialRho does not reject by the same tests (the partial pass's scan).
  void PossiblePartners(int index_a, std::vector<int>* out, int max_count_difference = 0) const;

  // Eq. (32): M(k) = (1/N) sum_i H(p_i, p'_j) H'(p_i, p'_j), j = (i + k) mod N. nullopt when the
  // shift violates (36) or (37) or a segment pairing fails (17); the segment counts must agree.
  std::optional<double> M(int index_a, int index_b, int shift) const;

  // The largest d (image 1) and d' (image 2) the pair may have: R, or the pose band.
  struct Bands {
    double in_image1 = 0;
    double in_image2 = 0;
  };
  Bands BandsOf(int index_a, int index_b) const;
  // The cheirality test of the pair's locations (true without geometry or with use_cheirality off).
  bool PassesCheirality(int index_a, int index_b) const;

 private:
  std::optional<double> M(int index_a, int index_b, int shift, const Bands& bands) const;
  // The parts of BandsOf (with geometry and use_pose_band): the pose sigma of the residual, and a
  // band from it.
  double PoseSigmaE(int index_a, int index_b) const;
  double PoseBand(double sigma_e, double line_norm) const;
  // H H' of segment ia of image 1 with segment ib of image 2 (indices into the sides' segments).
  std::optional<double> SegmentPairSupport(int ia, int ib, const Bands& bands) const;
  // d, d' within the bands and the cheirality test, as Rho starts; the bands and d, d' out.
  bool LocationsAgree(int index_a, int index_b, Bands* bands, double* d, double* d_prime) const;
  // Sum of H H' over the pairings of a's segments segments_a[i] with b's segments_b[(i + shift) % n]
  // (indices within each junction), after (36) and (37); nullopt when a test fails.
  std::optional<double> SubsetSupport(int index_a, int index_b, const int* segments_a, const int* segments_b, int n,
                                      int shift, const Bands& bands) const;

  // One image's junctions: segments of junction j at [first[j], first[j] + count[j]).
  struct Side {
    std::vector<int> first;
    std::vector<int> count;
    std::vector<Eigen::Vector2d> location;       // p0
    std::vector<Eigen::Vector3d> location_line;  // epipolar line of p0 in the other image, |(a,b)| = 1
    std::vector<double> location_line_norm;      // |(a,b)| of F p0 before normalising
    std::vector<Eigen::Matrix<double, 3, 6>> deviation;  // image 1 only, with geometry: G_k p0
    // With geometry: the cheirality test of each location, filled on first use (ParallaxOf).
    mutable std::vector<ParallaxFrame> parallax;
    mutable std::vector<double> parallax_tolerance;  // band_sigmas sqrt(sigma_v^2 + 2 location_sigma^2)
    mutable std::vector<char> parallax_known;
    std::vector<double> deviation_bound;  // image 1 only: the band of the largest sigma_d' over image 2's locations
    std::vector<OrientedSegment> segments;
    std::vector<Eigen::Vector2d> directions;      // segments[k].direction, contiguous for (36)-(37)
    std::vector<int> line_segments;               // JunctionSegment::line_segment of each
    std::vector<EndpointEpipolar> epipolar;       // of each end-point, into the other image
  };
  static Side MakeSide(const Junctions& junctions, const Eigen::Matrix3d& F);
  // side.parallax[index] under pose, computed on the first call.
  const ParallaxFrame& ParallaxOf(const Side& side, const PairGeometry& pose, int index) const;

  MatchingOptions options_;
  bool has_geometry_ = false;
  PairGeometry geometry_;          // with geometry: camera 2 from camera 1
  PairGeometry inverse_geometry_;  // and camera 1 from camera 2
  double min_sin_;  // sin(options.cyclic_order_min_angle_deg)
  Side side_a_;     // lines through F
  Side side_b_;     // lines through F^T
  // b's locations, x and y apart, for PossiblePartners' scan.
  std::vector<double> b_x_, b_y_;
};

}  // namespace sfm
