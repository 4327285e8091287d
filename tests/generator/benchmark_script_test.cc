// scripts/benchmark_junctions.sh writes the sequences it generates into $WORK, like the other
// benchmark scripts (benchmark_matching.sh, benchmark_backend.sh). The script is run for real with
// stand-ins: a `cmake` on PATH that does nothing and a benchmark_junctions in $BUILD/bin that
// records its arguments, so the test costs milliseconds and checks what the script passes on.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/test_data.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

void WriteExecutable(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  fs::permissions(path, fs::perms::owner_all, fs::perm_options::add);
}

// Runs the script with `environment` (VAR=value words) and `arguments`; returns the arguments the
// stand-in benchmark_junctions received, one per element.
std::vector<std::string> RunScript(const std::string& scratch, const std::string& environment,
                                   const std::string& arguments) {
  const fs::path root(scratch);
  WriteExecutable(root / "stub" / "cmake", "#!/bin/sh\nexit 0\n");
  WriteExecutable(root / "build" / "bin" / "benchmark_junctions",
                  "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done > \"" +
                      (root / "args.txt").string() + "\"\n");
  fs::remove(root / "args.txt");
  const std::string script = (fs::path(testing::SourceDir()) / "scripts" / "benchmark_junctions.sh").string();
  const std::string command = "env -u WORK PATH=\"" + (root / "stub").string() + ":$PATH\" BUILD=\"" +
                              (root / "build").string() + "\" " + environment + " bash \"" + script + "\" " +
                              arguments + " > /dev/null 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(root / "args.txt");
  std::vector<std::string> received;
  for (std::string line; std::getline(in, line);) received.push_back(line);
  return received;
}

// The value of the last `flag` (gflags keeps the last one), or "" when absent.
std::string LastFlag(const std::vector<std::string>& arguments, const std::string& flag) {
  std::string value;
  for (size_t i = 0; i + 1 < arguments.size(); ++i) {
    if (arguments[i] == flag) value = arguments[i + 1];
  }
  return value;
}

TEST(BenchmarkJunctionsScriptTest, GeneratesIntoWork) {
  const std::string scratch = testing::MakeScratchDir("benchmark_junctions_script");
  const std::vector<std::string> received = RunScript(scratch, "WORK=/tmp/some-work", "r.md --frames 3");
  EXPECT_EQ(LastFlag(received, "--work_dir"), "/tmp/some-work");
  EXPECT_EQ(LastFlag(received, "--output"), "r.md");
  EXPECT_EQ(LastFlag(received, "--frames"), "3");
}

TEST(BenchmarkJunctionsScriptTest, DefaultWorkAndExplicitFlagStillWins) {
  const std::string scratch = testing::MakeScratchDir("benchmark_junctions_script_default");
  EXPECT_EQ(LastFlag(RunScript(scratch, "", "r.md"), "--work_dir"), "/tmp/junction_benchmark");
  EXPECT_EQ(LastFlag(RunScript(scratch, "WORK=/tmp/some-work", "r.md --work_dir /tmp/given"), "--work_dir"),
            "/tmp/given");
}

}  // namespace
}  // namespace sfm
