// Test entry point: glog to stderr, and a fixed seed before each test so runs are repeatable.
#include <cstdlib>

#include <glog/logging.h>
#include <gtest/gtest.h>

namespace {

class ReseedListener : public testing::EmptyTestEventListener {
  void OnTestStart(const testing::TestInfo&) override { std::srand(42); }
};

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  google::InitGoogleLogging(argv[0]);
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = 1;  // warnings and up: keep test output readable
  testing::UnitTest::GetInstance()->listeners().Append(new ReseedListener);
  return RUN_ALL_TESTS();
}
