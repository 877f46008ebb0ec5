// The disk: why capture pauses, in words, and the statvfs probe.
#include "daemon/storage/disk_space.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;

TEST(DiskSpace, PauseReasonsInWords) {
  EXPECT_EQ(diskPauseReason({.free_bytes = 2ull << 30}, 1ull << 30, "/data"), "");
  EXPECT_EQ(diskPauseReason({.free_bytes = 512ull << 20}, 1ull << 30, "/data"),
            "512.0 MiB free on /data, below the 1.0 GiB reserve");
  EXPECT_NE(
      diskPauseReason({.free_bytes = 2ull << 30, .read_only = true}, 0, "/data").find("read-only"),
      std::string::npos);
  EXPECT_EQ(formatBytes(512), "512 B");
  const auto probed = makeStatvfsDiskProbe()->probe(fs::temp_directory_path() / "not" / "yet");
  ASSERT_TRUE(probed);  // the nearest existing parent's filesystem
  EXPECT_GT(probed->total_bytes, 0u);
}

}  // namespace
}  // namespace glarecam::daemon
