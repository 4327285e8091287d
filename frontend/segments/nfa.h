// A-contrario validation of a segment (Desolneux, Moisan & Morel; as used by LSD and EDLines):
// the expected number of segments at least this well aligned in an image of pure noise.
#pragma once

namespace sfm {

// log10 of the binomial tail P[X >= k] for X ~ B(n, p), 0 <= k <= n, 0 < p < 1.
double Log10BinomialTail(int n, int k, double p);

// log10 of the number of false alarms of a segment sampled at n points of which k have a gradient
// within p*180 degrees of the segment's normal, in an image of width x height pixels: the number of
// tests is (width*height)^2, one per pair of end-points.
double Log10Nfa(int n, int k, double p, int width, int height);

// The same with the number of tests given (log10): for candidates that are sub-runs of edge chains,
// the number of such sub-runs (see fast_segments.cc), not every pair of pixels.
double Log10Nfa(int n, int k, double p, double log10_tests);

}  // namespace sfm
