#include "frontend/tracks/tracks_csv.h"

#include <glog/logging.h>

namespace sfm {

std::string TracksCsv(const std::vector<JunctionTrack>& tracks, const std::vector<Junctions>& frames) {
  std::string csv = "track_id,frame,junction_id\n";
  for (const JunctionTrack& track : tracks) {
    for (const TrackView& view : track.views) {
      CHECK(view.frame >= 0 && view.frame < static_cast<int>(frames.size()) && view.junction >= 0 &&
            view.junction < static_cast<int>(frames[view.frame].size()))
          << "track " << track.id << " views junction " << view.junction << " of frame " << view.frame;
      csv += std::to_string(track.id) + "," + std::to_string(view.frame) + "," +
             std::to_string(frames[view.frame][view.junction].id) + "\n";
    }
  }
  return csv;
}

}  // namespace sfm
