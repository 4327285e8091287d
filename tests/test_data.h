// Where tests find their inputs (the repository, a scratch directory, ../shared/data) and how they
// read files.
#pragma once

#include <map>
#include <string>

namespace sfm::testing {

// The repository's top directory (tests run with it as working directory).
std::string SourceDir();

// A fresh, empty directory for one test's files, under the build tree.
std::string MakeScratchDir(const std::string& name);

// ../shared/data/<name> beside the repository, or "" when it is absent (tests then GTEST_SKIP).
std::string SharedDataDir(const std::string& name);

// The bytes of the file at `path` ("" when it cannot be read).
std::string ReadFile(const std::string& path);

// Relative path -> bytes of every regular file under `root`.
std::map<std::string, std::string> ReadTree(const std::string& root);

}  // namespace sfm::testing
