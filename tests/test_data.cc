#include "tests/test_data.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sfm::testing {
namespace fs = std::filesystem;

std::string SourceDir() {
  const char* dir = std::getenv("SFM_SOURCE_DIR");
  return dir ? dir : fs::current_path().string();
}

std::string MakeScratchDir(const std::string& name) {
  const char* binary = std::getenv("SFM_BINARY_DIR");
  const fs::path root = binary ? fs::path(binary) / "test_scratch" : fs::temp_directory_path() / "sfm_test_scratch";
  const fs::path dir = root / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string SharedDataDir(const std::string& name) {
  const fs::path dir = fs::path(SourceDir()) / ".." / "shared" / "data" / name;
  return fs::is_directory(dir) ? fs::canonical(dir).string() : std::string();
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::map<std::string, std::string> ReadTree(const std::string& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) files[fs::relative(entry.path(), root).string()] = ReadFile(entry.path().string());
  }
  return files;
}

}  // namespace sfm::testing
