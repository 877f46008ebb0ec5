#include "daemon/storage/disk_space.h"

#include <fmt/format.h>
#include <sys/statvfs.h>

#include <array>
#include <cerrno>
#include <system_error>

namespace glarecam::daemon {

namespace {

class StatvfsDiskProbe final : public DiskProbe {
 public:
  Result<DiskState> probe(const std::filesystem::path& path) override {
    std::filesystem::path existing = path;
    std::error_code error;
    while (!existing.empty() && !std::filesystem::exists(existing, error) &&
           existing != existing.parent_path())
      existing = existing.parent_path();
    struct statvfs fs {};
    if (statvfs(existing.empty() ? "." : existing.c_str(), &fs) != 0)
      return ioError(
          fmt::format("{}: cannot examine its filesystem: {}", path.string(), errnoText(errno)));
    return DiskState{.free_bytes = std::uint64_t(fs.f_bavail) * fs.f_frsize,
                     .total_bytes = std::uint64_t(fs.f_blocks) * fs.f_frsize,
                     .read_only = (fs.f_flag & ST_RDONLY) != 0};
  }
};

}  // namespace

std::unique_ptr<DiskProbe> makeStatvfsDiskProbe() { return std::make_unique<StatvfsDiskProbe>(); }

std::uint64_t treeBytes(const std::filesystem::path& path) {
  std::error_code error;
  std::uint64_t bytes = 0;
  const auto status = std::filesystem::symlink_status(path, error);
  if (std::filesystem::is_regular_file(status)) return std::filesystem::file_size(path, error);
  if (!std::filesystem::is_directory(status)) return 0;
  for (std::filesystem::recursive_directory_iterator it(path, error), end; !error && it != end;
       it.increment(error)) {
    if (it->is_regular_file(error) && !it->is_symlink(error)) {
      const std::uintmax_t size = it->file_size(error);
      if (!error) bytes += size;
      error.clear();
    }
  }
  return bytes;
}

std::string formatBytes(std::uint64_t bytes) {
  static constexpr std::array kUnits{"KiB", "MiB", "GiB", "TiB", "PiB"};
  if (bytes < 1024) return fmt::format("{} B", bytes);
  double value = double(bytes) / 1024;
  std::size_t unit = 0;
  while (value >= 1024 && unit + 1 < kUnits.size()) {
    value /= 1024;
    ++unit;
  }
  return fmt::format("{:.1f} {}", value, kUnits[unit]);
}

std::string diskPauseReason(const DiskState& state, std::uint64_t reserve_bytes,
                            const std::filesystem::path& path) {
  if (state.read_only)
    return fmt::format("{} is on a read-only filesystem (remounted after errors?)", path.string());
  if (state.free_bytes < reserve_bytes)
    return fmt::format("{} free on {}, below the {} reserve", formatBytes(state.free_bytes),
                       path.string(), formatBytes(reserve_bytes));
  return {};
}

}  // namespace glarecam::daemon
