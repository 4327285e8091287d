// Landmarks triangulated a second time, on an adjustment's refined poses, joined to the adjusted
// ones. docs/tracks_and_triangulation.md, "Re-triangulation on the refined poses".
#pragma once

#include "backend/triangulation/landmarks.h"

namespace sfm {

// Which landmarks of the second triangulation the map takes.
enum class RetriangulatedLandmarks {
  // Only those of tracks that have no landmark yet: a junction track with no point, a segment track
  // none of whose views any line observes. An adjusted landmark was solved jointly with the poses
  // and its observations passed the adjustment's outlier tests; solved again on the same poses it
  // would land where it is (its block is at a minimum of the joint cost given the poses).
  kAddNew,
  // All of them, in place of the adjusted ones (kept to measure the difference).
  kReplace,
};

struct LandmarkMergeReport {
  int points_added = 0;
  int lines_added = 0;
  int lines_linked_to_existing_point = 0;  // new lines whose junction point was already in the map
};

// Joins `retriangulated` (landmarks of the same tracks and frames) to `landmarks` as `which` says.
// kAddNew: a point is new when no point of `landmarks` has its track_id; a line is new when none of
// its observations (frame, junction, segment) is one of a line of `landmarks`. New ones are
// appended in their order; a new line's point_landmark becomes the index of its track's point in
// the joined map (the existing point when the track had one, the line's end0 then moved to it, as
// the adjustment keeps end0 at the point), or -1. The existing landmarks are not changed.
// kReplace: `landmarks` becomes `retriangulated`. point_landmark of `retriangulated` must index its
// points or be -1 (CHECKed).
void MergeRetriangulatedLandmarks(const Landmarks& retriangulated, RetriangulatedLandmarks which,
                                  Landmarks* landmarks, LandmarkMergeReport* report = nullptr);

}  // namespace sfm
