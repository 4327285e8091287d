// The output directory as one unit (SPEC section 2): what a committed, a failed and an interrupted
// run leave, the lock, and the refusal to replace what is not an earlier output.
#include "util/output_directory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::vector<std::string> kEntries = {"junctions", "metrics.json", "report.html"};

void WriteText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// Every name in `dir`, recursively, relative to it.
std::set<std::string> Listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    names.insert(fs::relative(entry.path(), dir).string());
  return names;
}

class OutputDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = testing::MakeScratchDir(std::string("output_directory_") +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    target_ = scratch_ / "out";
  }

  // An earlier run's output: metrics.json and junctions/000000.json .. 000039.json.
  void WriteEarlierOutput() {
    fs::create_directories(target_ / "junctions");
    for (int i = 0; i < 40; ++i)
      WriteText(target_ / "junctions" / (std::to_string(100000 + i) + ".json"), "{}");
    WriteText(target_ / "metrics.json", "{\"frames\": 40}");
  }

  fs::path scratch_, target_;
};

TEST_F(OutputDirectoryTest, CommitMovesTheNewContentsIntoPlaceAndLeavesNothingBeside) {
  std::unique_ptr<OutputDirectory> directory;
  ASSERT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &directory).ok());
  EXPECT_FALSE(fs::exists(target_)) << "nothing at the target until the commit";
  WriteText(fs::path(directory->staging()) / "metrics.json", "{\"frames\": 6}");
  ASSERT_TRUE(directory->Commit().ok());
  directory.reset();
  EXPECT_EQ(Listing(scratch_), (std::set<std::string>{"out", "out/metrics.json"}));
}

// Issue 18, item 2: a 6-frame run into a 40-frame run's output left the 40 old junction files.
TEST_F(OutputDirectoryTest, ASuccessfulRunReplacesTheEarlierOutputWhole) {
  WriteEarlierOutput();
  std::unique_ptr<OutputDirectory> directory;
  ASSERT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &directory).ok());
  fs::create_directory(fs::path(directory->staging()) / "junctions");
  WriteText(fs::path(directory->staging()) / "junctions" / "000000.json", "{}");
  WriteText(fs::path(directory->staging()) / "metrics.json", "{\"frames\": 6}");
  ASSERT_TRUE(directory->Commit().ok());
  directory.reset();
  EXPECT_EQ(Listing(scratch_),
            (std::set<std::string>{"out", "out/metrics.json", "out/junctions", "out/junctions/000000.json"}));
  EXPECT_EQ(testing::ReadFile(target_ / "metrics.json"), "{\"frames\": 6}");
}

// Issue 18, item 1: a failed run half-wrote. Without a commit the earlier output is untouched, and
// where there was none (parents included) nothing is left.
TEST_F(OutputDirectoryTest, AFailedRunLeavesTheEarlierOutputAsItWas) {
  WriteEarlierOutput();
  const std::map<std::string, std::string> before = testing::ReadTree(target_.string());
  {
    std::unique_ptr<OutputDirectory> directory;
    ASSERT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &directory).ok());
    WriteText(fs::path(directory->staging()) / "metrics.json", "{\"frames\": 6}");
  }
  EXPECT_EQ(testing::ReadTree(target_.string()), before);
  EXPECT_EQ(Listing(scratch_).count(".out.lock"), 0u);
  EXPECT_EQ(fs::directory_iterator(scratch_)->path().filename(), "out") << "only the output beside it";

  const fs::path deep = scratch_ / "a" / "b" / "out";
  {
    std::unique_ptr<OutputDirectory> directory;
    ASSERT_TRUE(OutputDirectory::Open(deep.string(), kEntries, &directory).ok());
    WriteText(fs::path(directory->staging()) / "metrics.json", "{}");
  }
  EXPECT_FALSE(fs::exists(scratch_ / "a")) << "the parents it created are removed again";
}

TEST_F(OutputDirectoryTest, RefusesToReplaceWhatIsNotAnEarlierOutput) {
  fs::create_directories(target_);
  WriteText(target_ / "thesis.tex", "mine");
  std::unique_ptr<OutputDirectory> directory;
  const Status status = OutputDirectory::Open(target_.string(), kEntries, &directory);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(target_.string() + ": holds 'thesis.tex'"));
  EXPECT_TRUE(fs::exists(target_ / "thesis.tex"));

  WriteText(scratch_ / "file", "x");
  const Status file = OutputDirectory::Open((scratch_ / "file").string(), kEntries, &directory);
  ASSERT_FALSE(file.ok());
  EXPECT_THAT(file.message(), HasSubstr("exists and is not a directory"));
  // A leftover of a killed earlier run's atomic write is part of that run's output.
  fs::remove(target_ / "thesis.tex");
  WriteText(target_ / "report.html.tmp.12345", "partial");
  EXPECT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &directory).ok());
}

TEST_F(OutputDirectoryTest, ASecondRunIntoTheSameDirectoryIsRefused) {
  std::unique_ptr<OutputDirectory> first, second;
  ASSERT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &first).ok());
  const Status refused = OutputDirectory::Open(target_.string(), kEntries, &second);
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.message(),
              HasSubstr("another junction_sfm run (pid " + std::to_string(getpid()) + ") is writing"));
  // The same directory by another spelling is the same lock.
  const Status by_dot = OutputDirectory::Open((scratch_ / "." / "out" / "").string(), kEntries, &second);
  EXPECT_FALSE(by_dot.ok());
  ASSERT_TRUE(first->Commit().ok());
  first.reset();
  EXPECT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &second).ok())
      << "free again after the commit";
}

TEST_F(OutputDirectoryTest, AKilledRunsStagingDirectoryIsRemovedByTheNextRun) {
  fs::create_directories(scratch_ / ".out.staging-AbC123" / "junctions");
  WriteText(scratch_ / ".out.staging-AbC123" / "junctions" / "000000.json", "{}");
  WriteText(scratch_ / ".out.lock", "999999\n");  // a lock file nobody holds
  std::unique_ptr<OutputDirectory> directory;
  ASSERT_TRUE(OutputDirectory::Open(target_.string(), kEntries, &directory).ok());
  EXPECT_FALSE(fs::exists(scratch_ / ".out.staging-AbC123"));
  ASSERT_TRUE(directory->Commit().ok());
  EXPECT_EQ(Listing(scratch_), (std::set<std::string>{"out"}));
}

TEST_F(OutputDirectoryTest, RemoveTreeDoesNotFollowSymbolicLinks) {
  fs::create_directories(scratch_ / "keep");
  WriteText(scratch_ / "keep" / "precious", "x");
  fs::create_directories(scratch_ / "tree" / "a" / "b");
  WriteText(scratch_ / "tree" / "a" / "b" / "f", "x");
  fs::create_directory_symlink(scratch_ / "keep", scratch_ / "tree" / "a" / "link");
  EXPECT_TRUE(RemoveTreeNoAlloc((scratch_ / "tree").c_str()));
  EXPECT_FALSE(fs::exists(scratch_ / "tree"));
  EXPECT_TRUE(fs::exists(scratch_ / "keep" / "precious"));
}

// Issue 18, item 3: SIGINT or SIGTERM while the outputs are written, over an earlier output, on
// the main thread or on a worker thread: exit 128 + signal, the earlier output as it was, nothing
// beside it.
void InterruptedChild(const fs::path& target, int write_end, bool signal_on_worker) {
  std::unique_ptr<OutputDirectory> directory;
  if (!OutputDirectory::Open(target.string(), kEntries, &directory).ok()) _exit(90);
  directory->RemoveOnSignals();
  fs::create_directory(fs::path(directory->staging()) / "junctions");
  for (int i = 0; i < 100; ++i) {
    WriteText(fs::path(directory->staging()) / "junctions" / (std::to_string(i) + ".json"), "{}");
  }
  std::thread worker([&] {
    if (signal_on_worker) {
      sigset_t set;
      sigemptyset(&set);
      pthread_sigmask(SIG_SETMASK, &set, nullptr);
    }
    pause();
  });
  if (signal_on_worker) {
    // Only the worker can receive it: the main thread blocks the signals for now.
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
  }
  if (write(write_end, "r", 1) != 1) _exit(91);
  if (signal_on_worker) {
    sleep(1);  // the worker receives the signal and passes it to this thread
    sigset_t set;
    sigemptyset(&set);
    pthread_sigmask(SIG_SETMASK, &set, nullptr);
  }
  for (;;) pause();
}

TEST_F(OutputDirectoryTest, SignalsRemoveTheStagingDirectoryAndKeepTheEarlierOutput) {
  WriteEarlierOutput();
  const std::map<std::string, std::string> before = testing::ReadTree(target_.string());
  for (const auto& [signal_number, on_worker] :
       {std::pair{SIGINT, false}, std::pair{SIGTERM, false}, std::pair{SIGTERM, true}}) {
    int pipe_ends[2];
    ASSERT_EQ(pipe(pipe_ends), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(pipe_ends[0]);
      InterruptedChild(target_, pipe_ends[1], on_worker);
    }
    close(pipe_ends[1]);
    char ready = 0;
    ASSERT_EQ(read(pipe_ends[0], &ready, 1), 1);
    close(pipe_ends[0]);
    ASSERT_EQ(kill(child, signal_number), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "signal " << signal_number;
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal_number);
    EXPECT_EQ(testing::ReadTree(target_.string()), before);
    EXPECT_EQ(Listing(scratch_).size(), Listing(target_).size() + 1) << "nothing beside the output";
  }
}

}  // namespace
}  // namespace sfm
