// glarecamd's output directory on a temporary directory: its three directories made, what a
// killed run left half-written removed (and nothing else), the stacks still to process, and
// whether a write would stick.
#include "daemon/storage/output_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::writeText;

// A directory that looks like a stack to the tree (its stack.json).
void makeStack(const fs::path& directory) {
  fs::create_directories(directory);
  writeText(directory / "stack.json", "{}");
}

std::vector<fs::path> entries(const fs::path& directory) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(directory)) found.push_back(entry.path());
  std::sort(found.begin(), found.end());
  return found;
}

TEST(OutputTree, PrepareMakesItsThreeDirectories) {
  TempDir dir;
  const OutputTree tree(dir / "out");
  EXPECT_EQ(tree.stacks(), dir / "out" / "stacks");
  EXPECT_EQ(tree.results(), dir / "out" / "results");
  EXPECT_EQ(tree.days(), dir / "out" / "days");
  ASSERT_TRUE(tree.prepare());
  EXPECT_TRUE(fs::is_directory(tree.stacks()));
  EXPECT_TRUE(fs::is_directory(tree.results()));
  EXPECT_TRUE(fs::is_directory(tree.days()));
  EXPECT_TRUE(tree.prepare());  // again: nothing to do

  writeText(dir / "file", "not a directory");
  EXPECT_FALSE(OutputTree(dir / "file").prepare());
}

TEST(OutputTree, RemovesOnlyWhatAKilledRunLeftHalfWritten) {
  TempDir dir;
  const OutputTree tree(dir.path());
  ASSERT_TRUE(tree.prepare());
  const std::string staging(kTemporaryPrefix);
  makeStack(tree.stacks() / (staging + "20260621T080000Z-a40.00-x1"));
  makeStack(tree.stacks() / "20260621T070000Z-a40.00");
  fs::create_directories(tree.results() / (staging + "20260621T070000Z-a40.00-x2"));
  fs::create_directories(tree.results() / "20260621T060000Z-a40.00");
  fs::create_directories(tree.days() / "2026-06-21");
  writeText(tree.days() / "2026-06-21" / (staging + "sweep.csv-x3"), "half a table");
  writeText(tree.days() / "2026-06-21" / "sweep.csv", "a table");
  EXPECT_EQ(tree.removeLeftovers(), 3u);
  EXPECT_EQ(entries(tree.stacks()),
            (std::vector<fs::path>{tree.stacks() / "20260621T070000Z-a40.00"}));
  EXPECT_EQ(entries(tree.results()),
            (std::vector<fs::path>{tree.results() / "20260621T060000Z-a40.00"}));
  EXPECT_EQ(entries(tree.days() / "2026-06-21"),
            (std::vector<fs::path>{tree.days() / "2026-06-21" / "sweep.csv"}));
  EXPECT_EQ(tree.removeLeftovers(), 0u);
}

TEST(OutputTree, UnprocessedStacksHaveNeitherAResultNorAFailedMark) {
  TempDir dir;
  const OutputTree tree(dir.path());
  ASSERT_TRUE(tree.prepare());
  for (const char* id : {"e-new", "a-done", "b-failed", "c-new"}) makeStack(tree.stacks() / id);
  fs::create_directories(tree.stacks() / "d-not-a-stack");
  fs::create_directories(tree.results() / "a-done");
  writeText(tree.results() / "a-done" / "result.json", "{}");
  writeText(tree.results() / "b-failed.failed", "bad data\n");
  // A result directory without result.json is a result still being made: not done.
  fs::create_directories(tree.results() / "c-new");
  EXPECT_EQ(tree.unprocessedStacks(),
            (std::vector<fs::path>{tree.stacks() / "c-new", tree.stacks() / "e-new"}));
}

TEST(OutputTree, WritableWhenADirectoryCanBeMadeInStacks) {
  TempDir dir;
  const OutputTree tree(dir / "out");
  EXPECT_TRUE(tree.writable());                 // made by the check itself
  EXPECT_TRUE(entries(tree.stacks()).empty());  // the probe is gone
  // A refusal statvfs cannot see: stacks/ turned into a file.
  fs::remove(tree.stacks());
  writeText(tree.stacks(), "not a directory");
  EXPECT_FALSE(tree.writable());
}

}  // namespace
}  // namespace glarecam::daemon
