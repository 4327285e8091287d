// Where tests find their inputs: the repository, a scratch directory, and ../shared/data.
#pragma once

#include <string>

namespace sfm::testing {

// The repository's top directory (tests run with it as working directory).
std::string SourceDir();

// A fresh, empty directory for one test's files, under the build tree.
std::string MakeScratchDir(const std::string& name);

// ../shared/data/<name> beside the repository, or "" when it is absent (tests then GTEST_SKIP).
std::string SharedDataDir(const std::string& name);

}  // namespace sfm::testing
