#include "tests/test_data.h"

#include <cstdlib>
#include <filesystem>

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

}  // namespace sfm::testing
