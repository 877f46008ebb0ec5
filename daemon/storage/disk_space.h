// The output filesystem's state, as the daemon checks it before every capture: free space against
// the configured reserve, and whether it is mounted read-only (an SD card the kernel remounted
// read-only after errors). Behind an interface so that tests fill and empty a disk at will.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/error.h"

namespace glarecam::daemon {

struct DiskState {
  std::uint64_t free_bytes = 0;  // available to an unprivileged writer (statvfs f_bavail)
  std::uint64_t total_bytes = 0;
  bool read_only = false;
};

class DiskProbe {
 public:
  virtual ~DiskProbe() = default;
  // kIo naming the path when it cannot be examined.
  virtual Result<DiskState> probe(const std::filesystem::path& path) = 0;
};

// statvfs(3) of the filesystem holding `path` (or its nearest existing parent).
std::unique_ptr<DiskProbe> makeStatvfsDiskProbe();

// Why capture must pause, in words ("12.0 MiB free on /var/lib/glarecam, below the 1.0 GiB
// reserve"), or empty when it may go on.
std::string diskPauseReason(const DiskState& state, std::uint64_t reserve_bytes,
                            const std::filesystem::path& path);

// The bytes of the regular files under `path` (or of `path` itself, a file), symbolic links not
// followed: what a stack, a result or a directory of the output tree takes.
std::uint64_t treeBytes(const std::filesystem::path& path);

// "1.5 GiB", "12.0 MiB", "512 B".
std::string formatBytes(std::uint64_t bytes);

}  // namespace glarecam::daemon
