#include "frontend/junctions/junction_detector.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "frontend/junctions/classification.h"
#include "frontend/junctions/intersection.h"
#include "frontend/junctions/pair_probability.h"
#include "frontend/junctions/segment_grid.h"

namespace sfm {
namespace {

// A segment shorter than a pixel has no direction worth intersecting.
constexpr double kMinSegmentLengthPx = 1.0;
// Widens the candidate search a little so that rounding never drops a pair at the exact limit.
constexpr double kSearchMarginPx = 0.01;

// A node of the pair graph: one part (end-point 0, end-point 1, interior) of one segment.
int NodeOf(int segment, Contact contact) { return 3 * segment + static_cast<int>(contact); }
int SegmentOf(int node) { return node / 3; }
Contact ContactOf(int node) { return static_cast<Contact>(node % 3); }
int NodeA(const PairHit& hit) { return NodeOf(hit.segment_a, hit.contact_a); }
int NodeB(const PairHit& hit) { return NodeOf(hit.segment_b, hit.contact_b); }
int OtherNode(const PairHit& hit, int node) { return NodeA(hit) == node ? NodeB(hit) : NodeA(hit); }

// The pair graph: hits, and for each node the hits touching it.
class PairGraph {
 public:
  PairGraph(std::vector<PairHit> hits, int num_nodes) : hits_(std::move(hits)), begin_(num_nodes + 1, 0) {
    for (const PairHit& hit : hits_) {
      ++begin_[NodeA(hit) + 1];
      ++begin_[NodeB(hit) + 1];
    }
    for (int v = 0; v < num_nodes; ++v) begin_[v + 1] += begin_[v];
    incident_.resize(2 * hits_.size());
    std::vector<int> fill(begin_.begin(), begin_.end() - 1);
    for (int h = 0; h < static_cast<int>(hits_.size()); ++h) {
      incident_[fill[NodeA(hits_[h])]++] = h;
      incident_[fill[NodeB(hits_[h])]++] = h;
    }
  }

  const std::vector<PairHit>& hits() const { return hits_; }
  const PairHit& hit(int h) const { return hits_[h]; }
  // Hits touching node v: incident(v)[0 .. degree(v)).
  const int* incident(int v) const { return incident_.data() + begin_[v]; }
  int degree(int v) const { return begin_[v + 1] - begin_[v]; }

  // The hit joining nodes u and v, or -1.
  int Between(int u, int v) const {
    for (int k = 0; k < degree(u); ++k) {
      if (OtherNode(hit(incident(u)[k]), u) == v) return incident(u)[k];
    }
    return -1;
  }

 private:
  std::vector<PairHit> hits_;
  std::vector<int> begin_;
  std::vector<int> incident_;
};

// A junction being merged: member nodes and the hits among them.
struct Group {
  std::vector<int> nodes;
  std::vector<int> hits;
  double weight = 0;  // sum of the located hits' probabilities
  Eigen::Vector2d weighted_sum = Eigen::Vector2d::Zero();
  double score = 0;  // sum of all hits' probabilities

  void Add(const PairHit& hit, int index) {
    hits.push_back(index);
    score += hit.probability;
    if (hit.location) {
      weight += hit.probability;
      weighted_sum += hit.probability * *hit.location;
    }
  }
  bool Located() const { return weight > 0; }
  Eigen::Vector2d Location() const { return weighted_sum / weight; }
  bool HasSegment(int segment) const {
    return std::any_of(nodes.begin(), nodes.end(), [&](int v) { return SegmentOf(v) == segment; });
  }
};

// The node that can join `group` with the largest sum of pair probabilities, with its hits to the
// members, or -1: it must pass the pair test with every member (an end-point or an interior of a
// segment not yet in the group), and each located hit must lie within max_gap of the group's
// location. Other junctions are not looked at here: ChooseJunctions resolves the conflicts.
// `hits` is scratch space, passed in so that its allocation is reused across calls.
int BestJoiner(const PairGraph& graph, const Group& group, double max_gap, std::vector<int>* joiner_hits,
               std::vector<int>* scratch) {
  int best = -1;
  double best_sum = 0;
  std::vector<int>& hits = *scratch;
  const int anchor = group.nodes.front();
  for (int k = 0; k < graph.degree(anchor); ++k) {
    const int candidate = OtherNode(graph.hit(graph.incident(anchor)[k]), anchor);
    if (group.HasSegment(SegmentOf(candidate))) continue;
    hits.clear();
    double sum = 0;
    for (int member : group.nodes) {
      const int h = graph.Between(candidate, member);
      if (h < 0) break;
      const PairHit& hit = graph.hit(h);
      if (hit.location && group.Located() && (*hit.location - group.Location()).norm() > max_gap) break;
      hits.push_back(h);
      sum += hit.probability;
    }
    if (hits.size() == group.nodes.size() && sum > best_sum) {
      best = candidate;
      best_sum = sum;
      *joiner_hits = hits;
    }
  }
  return best;
}

// The junction of a merged group: its segments from the location to the member segments' far
// end-points, clockwise, typed.
Junction MakeJunction(const Group& group, const std::vector<SegmentLine>& lines, int id,
                      double collinear_tolerance_rad) {
  Junction junction;
  junction.id = id;
  junction.location = group.Location();
  junction.score = group.score;
  junction.segments.reserve(2 * group.nodes.size());
  for (int node : group.nodes) {
    const int s = SegmentOf(node);
    const Contact contact = ContactOf(node);
    if (contact != Contact::kEnd1) junction.segments.push_back({lines[s].p1, s});
    if (contact != Contact::kEnd0) junction.segments.push_back({lines[s].p0, s});
  }
  junction.type = OrderClockwiseAndClassify(&junction, collinear_tolerance_rad);
  return junction;
}

// The weight of a candidate for ChooseJunctions: the log-likelihood ratio of the end-points it
// explains. An assignment of end-points to junctions has the likelihood prod f(t) over the assigned
// end-points (eq. 5, t at the junction's location), so its log is a sum over end-points, each
// counted once, where the paper's score (the sum of pairwise probabilities) counts an end-point
// once per pair it is in (N - 1 times in an N-junction) and favours large junctions of weak pairs
// over one probable pair. Each end-point adds ln f(t) - ln sqrt(min_probability) (the per-end-point
// share of the pair threshold: a pair of two equal end-points at the threshold adds 0) when
// positive, else 0 (an end-point explained no better than the threshold allows counts as free). An
// interior (a T's bar, an X's crossing) moves nothing and adds nothing. A tiny floor keeps every
// weight positive (the branch and bound's bound needs it); a floor, not an addition, so that two
// junctions explaining the same end-points as one (two L's where four ends meet, against the X) do
// not outweigh it by the floor twice.
double EndLikelihoodWeight(const Group& group, const std::vector<SegmentLine>& lines,
                           const JunctionDetectorOptions& options) {
  const double baseline = 0.5 * std::log(options.min_probability);
  const Eigen::Vector2d at = group.Location();
  double weight = 0;
  for (int node : group.nodes) {
    if (ContactOf(node) == Contact::kThrough) continue;
    const double t = NearEndChange(lines[SegmentOf(node)], at).t;
    weight += std::max(0.0, std::log(options.endpoint_model.F(t)) - baseline);
  }
  return std::max(weight, 1e-9);
}

// Candidates conflict when they share an end-point node (an end-point belongs to one junction) or a
// pair (a pairing belongs to one junction); interiors may be shared (a bar holding several T's).
// Returns the indices, in candidate order, of the conflict-free set with the largest total score
// (EndLikelihoodWeight): among readings that all pass the pair test, the one that explains the most
// end-points best. Solved exactly per connected group of conflicting candidates by branch and bound
// (a vertex's conflicts involve a handful of candidates); a group larger than kMaxExact falls back
// to greedy by score.
std::vector<int> ChooseJunctions(const std::vector<Group>& candidates, size_t num_hits, int num_nodes) {
  constexpr int kMaxExact = 20;
  const int m = static_cast<int>(candidates.size());
  // Conflicting candidate pairs: candidates listed by key (end-point node, or num_nodes + hit) in
  // one flat array by a counting sort (candidates ascending within a key), every two with the same
  // key linked. Flat arrays, not a vector per node: the allocations otherwise cost more than the
  // search.
  const size_t num_keys = static_cast<size_t>(num_nodes) + num_hits;
  std::vector<int> key_begin(num_keys + 1, 0);
  auto for_each_key = [&](auto&& visit) {
    for (int c = 0; c < m; ++c) {
      for (int node : candidates[c].nodes) {
        if (ContactOf(node) != Contact::kThrough) visit(static_cast<size_t>(node), c);
      }
      for (int h : candidates[c].hits) visit(static_cast<size_t>(num_nodes) + h, c);
    }
  };
  for_each_key([&](size_t key, int) { ++key_begin[key + 1]; });
  for (size_t k = 0; k < num_keys; ++k) key_begin[k + 1] += key_begin[k];
  std::vector<int> keyed(key_begin[num_keys]);  // candidates, key after key
  {
    std::vector<int> fill(key_begin.begin(), key_begin.end() - 1);
    for_each_key([&](size_t key, int c) { keyed[fill[key]++] = c; });
  }
  // Each pair of candidates sharing a key, both ways, bucketed by the first (a counting sort), then
  // each candidate's few conflicts sorted and deduplicated: cheaper than sorting all the pairs.
  auto for_each_link = [&](auto&& link) {
    for (size_t k = 0; k < num_keys; ++k) {
      for (int x = key_begin[k]; x < key_begin[k + 1]; ++x) {
        for (int y = x + 1; y < key_begin[k + 1]; ++y) {
          link(keyed[x], keyed[y]);
          link(keyed[y], keyed[x]);
        }
      }
    }
  };
  std::vector<int> bucket_begin(m + 1, 0);
  for_each_link([&](int from, int) { ++bucket_begin[from + 1]; });
  for (int c = 0; c < m; ++c) bucket_begin[c + 1] += bucket_begin[c];
  std::vector<int> linked(bucket_begin[m]);
  {
    std::vector<int> fill(bucket_begin.begin(), bucket_begin.end() - 1);
    for_each_link([&](int from, int to) { linked[fill[from]++] = to; });
  }
  // conflicts of c: conflict_list[conflict_begin[c] .. conflict_begin[c + 1]), ascending.
  std::vector<int> conflict_begin(m + 1, 0), conflict_list;
  conflict_list.reserve(linked.size());
  for (int c = 0; c < m; ++c) {
    int* first = linked.data() + bucket_begin[c];
    int* last = linked.data() + bucket_begin[c + 1];
    std::sort(first, last);
    conflict_list.insert(conflict_list.end(), first, std::unique(first, last));
    conflict_begin[c + 1] = static_cast<int>(conflict_list.size());
  }
  struct Range {
    const int* b;
    const int* e;
    const int* begin() const { return b; }
    const int* end() const { return e; }
    bool empty() const { return b == e; }
  };
  auto conflicts = [&](int c) {
    return Range{conflict_list.data() + conflict_begin[c], conflict_list.data() + conflict_begin[c + 1]};
  };

  std::vector<int> component(m, -1);
  std::vector<bool> keep(m, false);
  std::vector<int> blocked(m, 0);
  std::vector<int> members;  // reused by every group: most groups are small and allocations add up
  std::vector<double> rest;
  std::vector<int> current, best;
  for (int root = 0; root < m; ++root) {
    if (component[root] >= 0) continue;
    // The connected group of conflicting candidates around root, strongest first.
    component[root] = root;
    if (conflicts(root).empty()) {
      keep[root] = true;
      continue;
    }
    members.assign(1, root);
    for (size_t k = 0; k < members.size(); ++k) {
      for (int other : conflicts(members[k])) {
        if (component[other] < 0) {
          component[other] = root;
          members.push_back(other);
        }
      }
    }
    std::stable_sort(members.begin(), members.end(), [&](int a, int b) {
      return candidates[a].score > candidates[b].score ||
             (candidates[a].score == candidates[b].score && a < b);
    });
    auto block = [&](int c, int delta) {
      for (int other : conflicts(c)) blocked[other] += delta;
    };
    if (static_cast<int>(members.size()) > kMaxExact) {
      for (int c : members) {
        if (blocked[c] > 0) continue;
        keep[c] = true;
        block(c, +1);
      }
      continue;
    }
    // Branch and bound: take or leave each member in score order; prune when even taking all the
    // rest cannot beat the best set found. Strict improvement keeps the earliest (greedy) set on ties;
    // a tie within rounding (kTie relative: sums of the same weights in another order) is a tie, so
    // that the greedy set, whose first member is the strongest single candidate, keeps it: of two
    // readings that explain the same end-points equally well, the one with fewer junctions.
    rest.assign(members.size() + 1, 0.0);
    for (int k = static_cast<int>(members.size()) - 1; k >= 0; --k)
      rest[k] = rest[k + 1] + candidates[members[k]].score;
    current.clear();
    best.clear();
    double best_score = -1;
    constexpr double kTie = 1e-12;
    // A generic lambda calling itself (not std::function): no allocation, calls can be inlined.
    auto search = [&](auto& self, size_t k, double score) -> void {
      if (score + rest[k] <= best_score + kTie * std::abs(best_score)) return;
      if (k == members.size()) {
        best_score = score;
        best = current;
        return;
      }
      const int c = members[k];
      if (blocked[c] == 0) {
        current.push_back(c);
        block(c, +1);
        self(self, k + 1, score + candidates[c].score);
        block(c, -1);
        current.pop_back();
      }
      self(self, k + 1, score);
    };
    search(search, 0, 0.0);
    for (int c : best) keep[c] = true;
  }
  std::vector<int> chosen;
  for (int c = 0; c < m; ++c) {
    if (keep[c]) chosen.push_back(c);
  }
  return chosen;
}

// The paper's N-junction rule (junctions at one location are one junction), applied after the
// end-likelihood choice: that choice counts each end-point once and may explain the ends meeting
// at a vertex by two junctions, each at its own pair's intersection a fraction of a pixel better,
// where the union of the two is itself a candidate (every pair between their segments passed the
// test within max_gap of the group's location: the growth made it one junction). Such two are
// replaced by their union, when no other chosen junction holds one of the union's pairs.
void MergeCoincidingJunctions(const std::vector<Group>& candidates, double max_gap,
                              std::vector<int>* chosen) {
  std::map<std::vector<int>, int> grown_by_nodes;
  for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
    if (candidates[c].nodes.size() < 3) continue;
    std::vector<int> key = candidates[c].nodes;
    std::sort(key.begin(), key.end());
    grown_by_nodes.emplace(std::move(key), c);
  }
  if (grown_by_nodes.empty()) return;
  // The pairs are tried in the order of the plain double loop over `kept` (i < j, first i, then
  // j), restarting after each merge, so the result is that loop's; but each pass finds the pairs
  // within 2 max_gap through the locations sorted by x, not by testing all K^2 / 2 pairs; counts
  // for each pair of segments the chosen junctions holding it, not by searching them all for each
  // merge tested; and after a merge at (i, j) retests only what the merge can have changed: the
  // rows before i failed, and stay failed except with the new junction at i, as long as no pair
  // lost a holder (the union holds every pair its parts held, the usual case); otherwise it starts
  // again from row 0 (a cluttered image has hundreds of junctions, where a repeated quadratic
  // scan would dominate the junction step).
  const double reach = 2 * max_gap;
  std::vector<Eigen::Vector2d> location;
  std::vector<int> by_x, near;
  // holders[h]: how many of the chosen junctions hold pair h.
  int num_hits = 0;
  for (const Group& group : candidates) {
    for (int h : group.hits) num_hits = std::max(num_hits, h + 1);
  }
  std::vector<int> holders(num_hits);
  for (int c : *chosen) {
    for (int h : candidates[c].hits) ++holders[h];
  }
  auto holds = [](const Group& group, int h) {
    return std::find(group.hits.begin(), group.hits.end(), h) != group.hits.end();
  };
  std::vector<double> sorted_x;
  std::vector<int>& kept = *chosen;
  // Merges kept[i] and kept[j] (i < j) if their union is a candidate whose pairs no third chosen
  // junction holds; true if it did.
  auto try_merge = [&](int i, int j) {
    const Group& a = candidates[kept[i]];
    const Group& b = candidates[kept[j]];
    // A grown group's hits all lie within max_gap of its location, so the two parts' locations
    // lie within 2 max_gap of each other: the cheap test first.
    if ((location[i] - location[j]).squaredNorm() > 4 * max_gap * max_gap) return false;
    std::vector<int> key = a.nodes;
    key.insert(key.end(), b.nodes.begin(), b.nodes.end());
    std::sort(key.begin(), key.end());
    if (std::adjacent_find(key.begin(), key.end()) != key.end()) return false;  // a shared node
    const auto found = grown_by_nodes.find(key);
    if (found == grown_by_nodes.end()) return false;
    const Group& both = candidates[found->second];
    // Taken by a third chosen junction: held by more chosen junctions than a and b account for
    // (a group holds each of its pairs once).
    for (int h : both.hits) {
      if (holders[h] > static_cast<int>(holds(a, h)) + static_cast<int>(holds(b, h))) return false;
    }
    return true;
  };
  int start_row = 0;  // rows before it: test only the pair with new_index
  int new_index = -1;
  bool merged = true;
  while (merged) {
    merged = false;
    const int num_kept = static_cast<int>(kept.size());
    location.resize(num_kept);
    by_x.resize(num_kept);
    for (int i = 0; i < num_kept; ++i) {
      location[i] = candidates[kept[i]].Location();
      by_x[i] = i;
    }
    std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return location[a].x() < location[b].x(); });
    sorted_x.resize(num_kept);
    for (int k = 0; k < num_kept; ++k) sorted_x[k] = location[by_x[k]].x();
    int merge_i = -1, merge_j = -1;
    for (int i = 0; i < start_row && merge_i < 0; ++i) {
      if (try_merge(i, new_index)) merge_i = i, merge_j = new_index;
    }
    for (int i = start_row; i < num_kept && merge_i < 0; ++i) {
      // The j > i within reach in x (a superset of those within reach), in increasing j.
      near.clear();
      const auto first = std::lower_bound(sorted_x.begin(), sorted_x.end(), location[i].x() - reach);
      for (auto it = first; it != sorted_x.end() && *it <= location[i].x() + reach; ++it) {
        const int j = by_x[it - sorted_x.begin()];
        if (j > i) near.push_back(j);
      }
      std::sort(near.begin(), near.end());
      for (size_t n = 0; n < near.size() && merge_i < 0; ++n) {
        if (try_merge(i, near[n])) merge_i = i, merge_j = near[n];
      }
    }
    if (merge_i < 0) break;
    const Group& a = candidates[kept[merge_i]];
    const Group& b = candidates[kept[merge_j]];
    const int union_candidate = grown_by_nodes.find([&] {
      std::vector<int> key = a.nodes;
      key.insert(key.end(), b.nodes.begin(), b.nodes.end());
      std::sort(key.begin(), key.end());
      return key;
    }())->second;
    const Group& both = candidates[union_candidate];
    bool lost_holder = false;
    for (const Group* part : {&a, &b}) {
      for (int h : part->hits) {
        --holders[h];
        lost_holder = lost_holder || !holds(both, h);
      }
    }
    for (int h : both.hits) ++holders[h];
    kept[merge_i] = union_candidate;
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(merge_j));
    new_index = merge_i;
    start_row = lost_holder ? 0 : merge_i;
    merged = true;
  }
  std::sort(chosen->begin(), chosen->end());
}

// Corners beyond taken end-points (docs/junctions.md, step 3). Where two true vertices lie a few
// pixels apart on one line (a segment A ends at the vertex W where a third edge X leaves it, and
// A's line goes on for a short stub, of another contrast, to the vertex V where a segment B ends),
// A's end-point belongs to W's junction, so B's end-point goes to the next line its ray meets (a T
// on X's interior just past X's end at W) or to none, and V gets no junction. This lets A's line
// serve V as well. B's end-point moves to the pair (A, B), at its eq. (6) point v, when
//   - A's end-point is held by another chosen junction W, v lies beyond W along A's line (A stops
//     shorter of v than of W: W stays the explanation of A's end-point), at least min_arm_px from
//     W (a shorter stub cannot be told from an end-point overshoot: the rule of the T against the
//     L) and from every other chosen junction (closer, it is not told apart from that one), and
//   - v explains B's end-point better than where it is: the per-end-point term of
//     EndLikelihoodWeight (the choice's own criterion) is larger at v than at B's T (the T is
//     replaced, the number of junctions is unchanged), or positive when B's end-point is in no
//     junction (the corner is added). A's end-point is not counted again: W already explains it.
// This is an end-point in two junctions, which in general was measured and rejected (precision
// 72 %, docs/junctions.md "Ambiguous cases"); here only on A's line beyond its junction, and only
// for an end-point that no junction explains better.
void CornersBeyondTakenEnds(const std::vector<Group>& candidates, const PairGraph& graph,
                            const std::vector<SegmentLine>& lines, const JunctionDetectorOptions& options,
                            std::vector<int>* chosen) {
  const int graph_nodes = 3 * static_cast<int>(lines.size());
  const double baseline = 0.5 * std::log(options.min_probability);
  auto end_term = [&](int node, const Eigen::Vector2d& at) {
    const SegmentLine& line = lines[SegmentOf(node)];
    // t of this end-point (eq. 8), not of the end nearer `at`.
    const bool end1 = ContactOf(node) == Contact::kEnd1;
    const Eigen::Vector2d end = end1 ? line.p1 : line.p0;
    const Eigen::Vector2d outward = end1 ? line.n : Eigen::Vector2d(-line.n);
    const double t = (end - at).dot(outward);
    return std::pair<double, double>(t, std::max(0.0, std::log(options.endpoint_model.F(t)) - baseline));
  };
  // The chosen junction holding each end-point node (index into *chosen, -1: none), and the pair
  // candidate of each hit (-1: none, a collinear link).
  std::vector<int> holder(graph_nodes, -1);
  for (int k = 0; k < static_cast<int>(chosen->size()); ++k) {
    for (int node : candidates[(*chosen)[k]].nodes) {
      if (ContactOf(node) != Contact::kThrough) holder[node] = k;
    }
  }
  std::vector<int> pair_of_hit(graph.hits().size(), -1);
  for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
    if (candidates[c].nodes.size() == 2) pair_of_hit[candidates[c].hits.front()] = c;
  }
  const int num_chosen = static_cast<int>(chosen->size());
  // A corner within min_arm_px of a chosen junction other than `k` (the T it would replace) is not
  // told apart from that junction: W, or any other.
  auto near_other_junction = [&](const Eigen::Vector2d& v, int k) {
    for (int j = 0; j < num_chosen; ++j) {
      if (j != k && ((candidates[(*chosen)[j]].Location() - v).norm() < options.min_arm_px)) return true;
    }
    return false;
  };
  auto try_end = [&](int b, int k, double current) {
    int best = -1;
    double best_term = current;
    for (int e = 0; e < graph.degree(b); ++e) {
      const int h = graph.incident(b)[e];
      const PairHit& hit = graph.hit(h);
      const int a = OtherNode(hit, b);
      if (!hit.location || ContactOf(a) == Contact::kThrough) continue;
      if (holder[a] < 0 || holder[a] == k || pair_of_hit[h] < 0) continue;
      const Eigen::Vector2d& v = *hit.location;
      const Eigen::Vector2d w = candidates[(*chosen)[holder[a]]].Location();
      if ((v - w).norm() < options.min_arm_px) continue;
      if (!(end_term(a, v).first < end_term(a, w).first)) continue;  // v beyond W along A's line
      const double term = end_term(b, v).second;
      // The scan over the chosen junctions last: it is the one test that is not O(1).
      if (term > best_term && !near_other_junction(v, k)) {
        best_term = term;
        best = pair_of_hit[h];
      }
    }
    return best;
  };
  for (int k = 0; k < num_chosen; ++k) {
    const Group& junction = candidates[(*chosen)[k]];
    if (junction.nodes.size() != 2) continue;
    int b = -1, interior = 0;
    for (int node : junction.nodes) {
      if (ContactOf(node) == Contact::kThrough)
        ++interior;
      else
        b = node;
    }
    if (interior != 1 || b < 0) continue;  // a T: one end-point, one interior
    const int best = try_end(b, k, end_term(b, junction.Location()).second);
    if (best >= 0) (*chosen)[k] = best;
  }
  // End-points in no junction: explained by nothing (0), so any corner beyond with a positive
  // term is an improvement; the corner is added.
  std::vector<int> added;
  for (int b = 0; b < graph_nodes; ++b) {
    if (ContactOf(b) == Contact::kThrough || holder[b] >= 0 || graph.degree(b) == 0) continue;
    const int best = try_end(b, -1, 0.0);
    if (best >= 0) added.push_back(best);
  }
  std::sort(added.begin(), added.end());
  added.erase(std::unique(added.begin(), added.end()), added.end());
  chosen->insert(chosen->end(), added.begin(), added.end());
  std::sort(chosen->begin(), chosen->end());
}

}  // namespace

Junctions DetectJunctions(const LineSegments& segments, const JunctionDetectorOptions& options) {
  const Status status = options.Check();
  CHECK(status.ok()) << status.message();
  const int n = static_cast<int>(segments.size());
  std::vector<SegmentLine> lines;
  lines.reserve(n);
  std::vector<bool> use(n);
  for (int i = 0; i < n; ++i) {
    lines.emplace_back(segments[i]);
    use[i] =
        segments[i].p0.allFinite() && segments[i].p1.allFinite() && lines[i].length >= kMinSegmentLengthPx;
  }

  std::vector<PairHit> hits;
  const double min_sine = CollinearMinSine(options);
  for (const auto& [a, b] : CandidatePairs(lines, use, options.max_gap_px + kSearchMarginPx,
                                           options.collinear_max_offset_px + kSearchMarginPx)) {
    if (std::optional<PairHit> hit = TestPair(lines, a, b, options, min_sine)) hits.push_back(*hit);
  }
  const PairGraph graph(std::move(hits), 3 * n);

  // Strongest pairs seed first; ties keep the input order, so the output is deterministic.
  std::vector<int> order(graph.hits().size());
  for (int h = 0; h < static_cast<int>(order.size()); ++h) order[h] = h;
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return graph.hit(a).probability > graph.hit(b).probability; });

  // Candidate junctions: from every accepted pair, the group grown greedily as if no other junction
  // existed, and the pair alone (which the choice below needs when the grown group conflicts where
  // the pair does not). Collinear pieces alone are one broken line, not a junction.
  // A pair's node set is its own (one hit per pair of segments), so only grown groups can repeat.
  std::vector<Group> candidates;
  candidates.reserve(order.size());
  std::set<std::vector<int>> seen_grown;
  std::vector<int> joiner_hits, joiner_scratch, key;
  // The grown group is built in `grown`, reused from seed to seed (its vectors keep their
  // capacity), and copied into the candidates only when new: most groups are found again from
  // each of their pairs.
  Group grown;
  for (int seed : order) {
    const PairHit& hit = graph.hit(seed);
    Group pair;
    pair.nodes = {NodeA(hit), NodeB(hit)};
    pair.Add(hit, seed);
    if (!pair.Located()) continue;
    // A joiner needs a pair with each member, so both nodes must have another pair.
    if (graph.degree(NodeA(hit)) > 1 && graph.degree(NodeB(hit)) > 1) {
      grown.nodes.assign(pair.nodes.begin(), pair.nodes.end());
      grown.hits.assign(pair.hits.begin(), pair.hits.end());
      grown.weight = pair.weight;
      grown.weighted_sum = pair.weighted_sum;
      grown.score = pair.score;
      while (true) {
        const int joiner = BestJoiner(graph, grown, options.max_gap_px, &joiner_hits, &joiner_scratch);
        if (joiner < 0) break;
        grown.nodes.push_back(joiner);
        for (int h : joiner_hits) grown.Add(graph.hit(h), h);
      }
      if (grown.nodes.size() > 2) {
        key.assign(grown.nodes.begin(), grown.nodes.end());
        std::sort(key.begin(), key.end());
        if (seen_grown.find(key) == seen_grown.end()) {
          seen_grown.insert(key);
          candidates.push_back(grown);
        }
      }
    }
    candidates.push_back(std::move(pair));
  }

  // The choice weighs each candidate by the end-points it explains (EndLikelihoodWeight); the
  // junctions keep the paper's score (the sum of their pair probabilities).
  std::vector<Group> weighted = candidates;
  for (Group& group : weighted) group.score = EndLikelihoodWeight(group, lines, options);
  std::vector<int> chosen = ChooseJunctions(weighted, graph.hits().size(), 3 * n);
  MergeCoincidingJunctions(candidates, options.max_gap_px, &chosen);
  CornersBeyondTakenEnds(candidates, graph, lines, options, &chosen);
  const double collinear_tolerance_rad = options.collinear_tolerance_deg * M_PI / 180.0;
  Junctions junctions;
  junctions.reserve(chosen.size());
  for (int c : chosen) {
    junctions.push_back(
        MakeJunction(candidates[c], lines, static_cast<int>(junctions.size()), collinear_tolerance_rad));
  }
  return junctions;
}

}  // namespace sfm
