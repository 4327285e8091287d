#include "tests/keypoints/strecha_entry.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "sequences/importers/imported_sequence.h"
#include "sequences/importers/strecha_importer.h"
#include "tests/test_data.h"

namespace sfm::testing {

std::string ImportStrechaEntryAtThreeTimesTheNoise(const std::string& scratch_name) {
  const std::string data = SharedDataDir("strecha-entry-P10");
  if (data.empty()) return "";
  const std::string out = (std::filesystem::path(MakeScratchDir(scratch_name)) / "sequence").string();
  ImportedSequence imported;
  Status status = ReadStrechaSequence(data, &imported);
  if (status.ok()) {
    SequenceWriteOptions write;
    write.odometry = write.odometry.Scaled(3);
    status = WriteImportedSequence(imported, write, out);
  }
  if (!status.ok()) {
    ADD_FAILURE() << status.message();
    return "";
  }
  return out;
}

}  // namespace sfm::testing
