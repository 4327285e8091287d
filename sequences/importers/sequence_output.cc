#include "sequences/importers/sequence_output.h"

#include <unistd.h>

#include "util/atomic_file.h"

namespace sfm {
namespace fs = std::filesystem;

fs::path NormalisedTarget(const std::string& output_dir) {
  fs::path target = fs::path(output_dir).lexically_normal();
  if (!target.has_filename()) target = target.parent_path();
  return target;
}

Status PrepareOutputDirectory(const fs::path& target, bool overwrite, fs::path* temporary) {
  if (target.empty()) return Status::Error("import: the output directory is not named");
  std::error_code error;
  if (fs::exists(target, error)) {
    if (!fs::is_directory(target, error))
      return Status::Error(target.string() + ": exists and is not a directory");
    if (!fs::is_empty(target, error) && !overwrite) {
      return Status::Error(target.string() +
                           ": exists and is not empty; choose another directory or overwrite it");
    }
  }
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory(parent.string()));
  *temporary = parent / ("." + target.filename().string() + ".importing." + std::to_string(::getpid()));
  fs::remove_all(*temporary, error);
  return EnsureWritableDirectory(temporary->string());
}

Status MoveIntoPlace(TemporaryDirectory* temporary, const fs::path& target) {
  std::error_code error;
  fs::path replaced;
  if (fs::exists(target, error)) {
    replaced =
        target.parent_path() / ("." + target.filename().string() + ".replaced." + std::to_string(::getpid()));
    fs::rename(target, replaced, error);
    if (error)
      return Status::Error(target.string() + ": cannot move the old directory aside (" + error.message() +
                           ")");
  }
  fs::rename(temporary->path(), target, error);
  if (error) {
    std::error_code ignored;
    if (!replaced.empty()) fs::rename(replaced, target, ignored);
    return Status::Error(target.string() + ": cannot rename the imported sequence into place (" +
                         error.message() + ")");
  }
  temporary->Release();
  if (!replaced.empty()) fs::remove_all(replaced, error);
  return Status::Ok();
}

}  // namespace sfm
