// Strecha entry-P10 imported for the keypoints tests: 768x512, the importer's default odometry
// noise times three, seed 1.
#pragma once

#include <string>

namespace sfm::testing {

// The sequence directory under a fresh scratch directory `scratch_name`, or "" when
// ../shared/data/strecha-entry-P10 is absent (the test then skips). Fails the test (ADD_FAILURE)
// and returns "" when the import fails.
std::string ImportStrechaEntryAtThreeTimesTheNoise(const std::string& scratch_name);

}  // namespace sfm::testing
