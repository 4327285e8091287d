#include "frontend/tracks/tracks.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace sfm {
namespace {

// counts[f] junctions in frame f, each with `num_segments` segments; junction j of frame f has
// id 100 f + j + 7 so that ids and indices differ.
std::vector<Junctions> MakeFrames(const std::vector<int>& counts, int num_segments) {
  std::vector<Junctions> frames(counts.size());
  for (size_t f = 0; f < counts.size(); ++f) {
    for (int j = 0; j < counts[f]; ++j) {
      Junction junction;
      junction.id = 100 * static_cast<int>(f) + j + 7;
      junction.location = Eigen::Vector2d(10.0 * j, 10.0 * f);
      for (int i = 0; i < num_segments; ++i) {
        junction.segments.push_back({junction.location + Eigen::Vector2d(30.0 + i, 5.0 * i), i});
      }
      frames[f].push_back(junction);
    }
  }
  return frames;
}

FramePairMatches Pair(int frame_a, int frame_b, std::vector<JunctionMatch> matches) {
  return {frame_a, frame_b, std::move(matches)};
}

std::vector<std::pair<int, int>> FrameJunctions(const JunctionTrack& track) {
  std::vector<std::pair<int, int>> views;
  for (const TrackView& view : track.views) views.emplace_back(view.frame, view.junction);
  return views;
}

using Views = std::vector<std::pair<int, int>>;

TEST(FramePairsToMatchTest, ConsecutiveAndTwoBack) {
  EXPECT_TRUE(FramePairsToMatch(0).empty());
  EXPECT_TRUE(FramePairsToMatch(1).empty());
  EXPECT_EQ(FramePairsToMatch(2), (std::vector<std::pair<int, int>>{{0, 1}}));
  EXPECT_EQ(FramePairsToMatch(4), (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}}));
}

TEST(BuildTracksTest, AChainOverFiveFramesBridgesAGapWithATwoBackMatch) {
  // Junction A is index 0 in frames 0, 1, 3, 4 and missed in frame 2; junction B is index 1 in
  // frames 0, 1, 3, 4 and index 0 in frame 2.
  const std::vector<Junctions> frames = MakeFrames({2, 2, 1, 2, 2}, 3);
  std::vector<FramePairMatches> pairs = {Pair(0, 1, {{0, 0, 0.9, 0}, {1, 1, 0.9, 0}}),
                                         Pair(0, 2, {{1, 0, 0.7, 0}}),
                                         Pair(1, 2, {{1, 0, 0.8, 0}}),
                                         Pair(1, 3, {{0, 0, 0.6, 0}, {1, 1, 0.6, 0}}),
                                         Pair(2, 3, {{0, 1, 0.8, 0}}),
                                         Pair(2, 4, {{0, 1, 0.7, 0}}),
                                         Pair(3, 4, {{0, 0, 0.9, 0}, {1, 1, 0.9, 0}})};
  TrackBuildReport report;
  std::vector<JunctionTrack> tracks = BuildTracks(frames, pairs, &report);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[0].id, 0);
  EXPECT_EQ(FrameJunctions(tracks[0]), (Views{{0, 0}, {1, 0}, {3, 0}, {4, 0}}));
  EXPECT_EQ(tracks[1].id, 1);
  EXPECT_EQ(FrameJunctions(tracks[1]), (Views{{0, 1}, {1, 1}, {2, 0}, {3, 1}, {4, 1}}));
  EXPECT_EQ(report.matches, 10);
  EXPECT_EQ(report.accepted, 10);
  EXPECT_EQ(report.rejected_junction_conflict, 0);
  EXPECT_EQ(report.rejected_segment_conflict, 0);

  // Without the two-back match (1, 3) of A, its track breaks in two.
  pairs[3].matches.erase(pairs[3].matches.begin());
  tracks = BuildTracks(frames, pairs);
  ASSERT_EQ(tracks.size(), 3u);
  EXPECT_EQ(FrameJunctions(tracks[0]), (Views{{0, 0}, {1, 0}}));
  EXPECT_EQ(FrameJunctions(tracks[1]), (Views{{0, 1}, {1, 1}, {2, 0}, {3, 1}, {4, 1}}));
  EXPECT_EQ(FrameJunctions(tracks[2]), (Views{{3, 0}, {4, 0}}));
}

TEST(BuildTracksTest, AnInconsistentComponentIsSplitAtItsWeakestMatch) {
  // 0:0 - 1:0 - 2:0 and the two-back 0:0 - 2:1 would put junctions 0 and 1 of frame 2 in one
  // track: the weakest of the three matches is rejected.
  const std::vector<Junctions> frames = MakeFrames({1, 1, 2}, 2);
  TrackBuildReport report;
  std::vector<JunctionTrack> tracks = BuildTracks(
      frames, {Pair(0, 1, {{0, 0, 0.9, 0}}), Pair(1, 2, {{0, 0, 0.8, 0}}), Pair(0, 2, {{0, 1, 0.5, 0}})},
      &report);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(FrameJunctions(tracks[0]), (Views{{0, 0}, {1, 0}, {2, 0}}));
  EXPECT_EQ(report.accepted, 2);
  EXPECT_EQ(report.rejected_junction_conflict, 1);

  // The same component with the two-back match the strongest: now 1:0 - 2:0 is the one dropped.
  tracks = BuildTracks(
      frames, {Pair(0, 1, {{0, 0, 0.9, 0}}), Pair(1, 2, {{0, 0, 0.8, 0}}), Pair(0, 2, {{0, 1, 0.95, 0}})},
      &report);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(FrameJunctions(tracks[0]), (Views{{0, 0}, {1, 0}, {2, 1}}));
  EXPECT_EQ(report.rejected_junction_conflict, 1);
}

TEST(BuildTracksTest, SegmentCorrespondencesComposeThroughTheShifts) {
  // One 4-segment junction over frames 0, 1, 3, 4 (missed in frame 2), joined by 0 -> 1 (shift 1),
  // the two-back 1 -> 3 (shift 3) and 3 -> 4 (shift 2).
  const std::vector<Junctions> frames = MakeFrames({1, 1, 0, 1, 1}, 4);
  TrackBuildReport report;
  const std::vector<JunctionTrack> tracks = BuildTracks(
      frames, {Pair(0, 1, {{0, 0, 0.9, 1}}), Pair(1, 3, {{0, 0, 0.8, 3}}), Pair(3, 4, {{0, 0, 0.7, 2}})},
      &report);
  ASSERT_EQ(tracks.size(), 1u);
  const JunctionTrack& track = tracks[0];
  ASSERT_EQ(track.views.size(), 4u);
  EXPECT_EQ(track.NumSegments(), 4);
  // Track segment s is frame 0's segment s; in frame 1 it is (s + 1) % 4, in frame 3
  // (s + 1 + 3) % 4 = s, in frame 4 (s + 1 + 3 + 2) % 4 = (s + 2) % 4.
  EXPECT_EQ(track.views[0].segments, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(track.views[1].segments, (std::vector<int>{1, 2, 3, 0}));
  EXPECT_EQ(track.views[2].segments, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(track.views[3].segments, (std::vector<int>{2, 3, 0, 1}));
  EXPECT_EQ(report.accepted, 3);
}

TEST(BuildTracksTest, AShiftThatDisagreesWithTheTrackIsRejected) {
  // 0 -> 1 shift 1 and 1 -> 2 shift 2 compose to 0 -> 2 shift 0; a two-back match with shift 1
  // would join two segments of frame 2 in one segment track.
  const std::vector<Junctions> frames = MakeFrames({1, 1, 1}, 3);
  TrackBuildReport report;
  const std::vector<JunctionTrack> consistent = BuildTracks(
      frames, {Pair(0, 1, {{0, 0, 0.9, 1}}), Pair(1, 2, {{0, 0, 0.8, 2}}), Pair(0, 2, {{0, 0, 0.5, 0}})},
      &report);
  ASSERT_EQ(consistent.size(), 1u);
  EXPECT_EQ(report.accepted, 3);
  EXPECT_EQ(consistent[0].views[1].segments, (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(consistent[0].views[2].segments, (std::vector<int>{0, 1, 2}));

  const std::vector<JunctionTrack> tracks = BuildTracks(
      frames, {Pair(0, 1, {{0, 0, 0.9, 1}}), Pair(1, 2, {{0, 0, 0.8, 2}}), Pair(0, 2, {{0, 0, 0.5, 1}})},
      &report);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(report.accepted, 2);
  EXPECT_EQ(report.rejected_segment_conflict, 1);
  EXPECT_EQ(tracks[0].views[1].segments, (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(tracks[0].views[2].segments, (std::vector<int>{0, 1, 2}));
}

TEST(BuildTracksTest, UnmatchedJunctionsMakeNoTrack) {
  const std::vector<Junctions> frames = MakeFrames({3, 3}, 2);
  EXPECT_TRUE(BuildTracks(frames, {}).empty());
  EXPECT_TRUE(BuildTracks({}, {}).empty());
  const std::vector<JunctionTrack> tracks = BuildTracks(frames, {Pair(0, 1, {{2, 1, 0.9, 1}})});
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(FrameJunctions(tracks[0]), (Views{{0, 2}, {1, 1}}));
  EXPECT_EQ(tracks[0].views[1].segments, (std::vector<int>{1, 0}));
}

// One junction per frame with counts[f] segments (ids as MakeFrames).
std::vector<Junctions> MakeOneJunctionFrames(const std::vector<int>& counts) {
  std::vector<Junctions> frames;
  for (size_t f = 0; f < counts.size(); ++f) frames.push_back(MakeFrames({1}, counts[f])[0]);
  return frames;
}

// A partial match: a junction of k segments against one of k + 1 (JunctionMatch::missing_a/_b).
JunctionMatch Partial(double similarity, int shift, int missing_a, int missing_b) {
  JunctionMatch match{0, 0, similarity, shift};
  match.missing_a = missing_a;
  match.missing_b = missing_b;
  return match;
}

TEST(BuildTracksTest, APartialMatchJoinsItsCommonSegmentsAndLeavesTheMissingOneOut) {
  // A Y with arms A, B, C. Frame 0: A, B, C = segments 0, 1, 2; frame 1: 1, 2, 0 (shift 1); frame
  // 2 misses B and sees an L with A = 1, C = 0; frame 3: 0, 1, 2 again. The matches 1 -> 2
  // (missing_a = 2, B of frame 1; frame 1 without it is C, A = 0, 1, onto the L's 0, 1: shift 0)
  // and 2 -> 3 (missing_b = 1, B; frame 3 without it is A, C = 0, 1; the L's C (0) is 1: shift 1)
  // are partial; 0 -> 1 (shift 1) and the two-back 1 -> 3 (shift 2) full.
  const std::vector<Junctions> frames = MakeOneJunctionFrames({3, 3, 2, 3});
  std::vector<FramePairMatches> pairs = {Pair(0, 1, {{0, 0, 0.9, 1}}), Pair(1, 2, {Partial(0.8, 0, 2, -1)}),
                                         Pair(1, 3, {{0, 0, 0.6, 2}}), Pair(2, 3, {Partial(0.7, 1, -1, 1)})};
  TrackBuildReport report;
  std::vector<JunctionTrack> tracks = BuildTracks(frames, pairs, &report);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(report.accepted, 4);
  EXPECT_EQ(FrameJunctions(tracks[0]), (Views{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  // Segment tracks A, B, C in the order of frame 0's segments; frame 2 has no B.
  ASSERT_EQ(tracks[0].NumSegments(), 3);
  EXPECT_EQ(tracks[0].views[0].segments, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(tracks[0].views[1].segments, (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(tracks[0].views[2].segments, (std::vector<int>{1, -1, 0}));
  EXPECT_EQ(tracks[0].views[3].segments, (std::vector<int>{0, 1, 2}));

  // Without the two-back match, B of frame 3 is paired with nothing: it is in no segment track
  // (a segment track needs two views), while A and C still run through the L of frame 2.
  pairs.erase(pairs.begin() + 2);
  tracks = BuildTracks(frames, pairs, &report);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(report.accepted, 3);
  ASSERT_EQ(tracks[0].NumSegments(), 3);
  EXPECT_EQ(tracks[0].views[2].segments, (std::vector<int>{1, -1, 0}));
  EXPECT_EQ(tracks[0].views[3].segments, (std::vector<int>{0, -1, 2}));
}

// A partial match with a T (or an X) on either side may be an occlusion seen with one arm hidden:
// it is not joined, and counted; the same L against a Y is joined, and a full T-T match is too.
TEST(BuildTracksTest, APartialMatchWithATOrAnXIsNotJoined) {
  std::vector<Junctions> frames = MakeOneJunctionFrames({2, 3});
  TrackBuildReport report;
  EXPECT_EQ(BuildTracks(frames, {Pair(0, 1, {Partial(0.8, 0, -1, 1)})}, &report).size(), 1u);
  EXPECT_EQ(report.skipped_partial_occlusion, 0);
  for (const JunctionType type : {JunctionType::kT, JunctionType::kX}) {
    frames[1][0].type = type;
    EXPECT_TRUE(BuildTracks(frames, {Pair(0, 1, {Partial(0.8, 0, -1, 1)})}, &report).empty());
    EXPECT_EQ(report.skipped_partial_occlusion, 1);
    EXPECT_EQ(report.accepted, 0);
  }
  std::vector<Junctions> two_ts = MakeOneJunctionFrames({3, 3});
  two_ts[0][0].type = two_ts[1][0].type = JunctionType::kT;
  EXPECT_EQ(BuildTracks(two_ts, {Pair(0, 1, {{0, 0, 0.9, 0}})}, &report).size(), 1u);
  EXPECT_EQ(report.skipped_partial_occlusion, 0);
}

TEST(BuildTracksTest, AnLMatchedOnlyToAYMakesTwoSegmentTracks) {
  // Frame 0: an L (A, C = 0, 1); frame 1: a Y (A, B, C = 0, 1, 2), B missing. The Y's B is in no
  // segment track, and the track's segment s is the L's segment s.
  const std::vector<Junctions> frames = MakeOneJunctionFrames({2, 3});
  const std::vector<JunctionTrack> tracks = BuildTracks(frames, {Pair(0, 1, {Partial(0.8, 0, -1, 1)})});
  ASSERT_EQ(tracks.size(), 1u);
  ASSERT_EQ(tracks[0].NumSegments(), 2);
  EXPECT_EQ(tracks[0].views[0].segments, (std::vector<int>{0, 1}));
  EXPECT_EQ(tracks[0].views[1].segments, (std::vector<int>{0, 2}));
}

TEST(BuildTracksTest, APartialMatchThatDisagreesWithTheTrackIsRejected) {
  // Frames 0 and 1: a Y (A, B, C = 0, 1, 2); frame 2: an L (A, C = 0, 1). 0 -> 1 full (shift 0) and
  // 0 -> 2 partial (missing_a = 1, shift 0: A -> A, C -> C) agree; a weaker 1 -> 2 with shift 1
  // (A -> C, C -> A) would put both L segments into one segment track with A.
  const std::vector<Junctions> frames = MakeOneJunctionFrames({3, 3, 2});
  TrackBuildReport report;
  const std::vector<JunctionTrack> tracks =
      BuildTracks(frames,
                  {Pair(0, 1, {{0, 0, 0.9, 0}}), Pair(0, 2, {Partial(0.8, 0, 1, -1)}),
                   Pair(1, 2, {Partial(0.7, 1, 1, -1)})},
                  &report);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(report.accepted, 2);
  EXPECT_EQ(report.rejected_segment_conflict, 1);
  EXPECT_EQ(tracks[0].views[2].segments, (std::vector<int>{0, -1, 1}));
}

TEST(BuildTracksDeathTest, AMatchOutsideTheFramesIsAProgrammerError) {
  const std::vector<Junctions> frames = MakeFrames({1, 1}, 2);
  EXPECT_DEATH(BuildTracks(frames, {Pair(0, 1, {{0, 1, 0.9, 0}})}), "outside frames");
  EXPECT_DEATH(BuildTracks(frames, {Pair(0, 1, {{0, 0, 0.9, 2}})}), "shift 2 for 2 segments");
  // Partial matches: the larger junction must have one segment more, and the shift is over k.
  const std::vector<Junctions> l_and_y = MakeOneJunctionFrames({2, 3});
  EXPECT_DEATH(BuildTracks(frames, {Pair(0, 1, {Partial(0.9, 0, -1, 1)})}),
               "partial match between junctions");
  EXPECT_DEATH(BuildTracks(l_and_y, {Pair(0, 1, {Partial(0.9, 0, 1, -1)})}),
               "partial match between junctions");
  EXPECT_DEATH(BuildTracks(l_and_y, {Pair(0, 1, {Partial(0.9, 0, 0, 1)})}), "two missing segments");
  EXPECT_DEATH(BuildTracks(l_and_y, {Pair(0, 1, {Partial(0.9, 0, -1, 3)})}), "missing segment 3 of 3");
  EXPECT_DEATH(BuildTracks(l_and_y, {Pair(0, 1, {Partial(0.9, 2, -1, 1)})}), "shift 2 for 2 segments");
  EXPECT_DEATH(BuildTracks(l_and_y, {Pair(0, 1, {{0, 0, 0.9, 0}})}), "full match between junctions");
}

}  // namespace
}  // namespace sfm
