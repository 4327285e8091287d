#include "frontend/tracks/tracks_csv.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

TEST(TracksCsvTest, WritesOneRowPerViewWithTheJunctionIds) {
  std::vector<Junctions> frames(3);
  for (int f = 0; f < 3; ++f) {
    for (int j = 0; j < 2; ++j) {
      Junction junction;
      junction.id = 10 * f + 3 * j + 1;  // frame 0: 1, 4; frame 1: 11, 14; frame 2: 21, 24
      frames[f].push_back(junction);
    }
  }
  std::vector<JunctionTrack> tracks(2);
  tracks[0].id = 0;
  tracks[0].views = {{0, 1, {}}, {1, 0, {}}, {2, 1, {}}};
  tracks[1].id = 1;
  tracks[1].views = {{1, 1, {}}, {2, 0, {}}};
  EXPECT_EQ(TracksCsv(tracks, frames),
            "track_id,frame,junction_id\n"
            "0,0,4\n"
            "0,1,11\n"
            "0,2,24\n"
            "1,1,14\n"
            "1,2,21\n");
  EXPECT_EQ(TracksCsv({}, frames), "track_id,frame,junction_id\n");
}

}  // namespace
}  // namespace sfm
