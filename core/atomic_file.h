// Crash-safe writes. A file or directory appears under its final name only complete: it is
// built under a hidden temporary sibling name, fsynced, renamed into place, and the parent
// directory fsynced. After a crash a reader sees the old version or the new one, never half.
// Leftover temporaries start with ".tmp-" and are removed by removeStaleTemporaries().
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>

#include "core/error.h"

namespace glarecam {

// Writes bytes to path atomically (replacing an existing file).
Status writeFileAtomic(const std::filesystem::path& path, std::span<const std::byte> bytes);
Status writeFileAtomic(const std::filesystem::path& path, std::string_view text);

// For writers that need a file name (libraries that open files themselves): a new empty
// temporary sibling of `target`, and its commit (fsync, rename over target, fsync the parent;
// the temporary is removed if that fails). Callers remove the temporary if they give up.
Result<std::filesystem::path> createTemporarySibling(const std::filesystem::path& target);
Status commitTemporary(const std::filesystem::path& temp, const std::filesystem::path& target);

// Writes a file's contents durably in place (no rename): for files inside a staging directory.
Status writeFileDurable(const std::filesystem::path& path, std::span<const std::byte> bytes);

Status fsyncPath(const std::filesystem::path& path);

// An output directory, created with its parents when missing: kBadInput when something else
// (a file) is at the path, kIo when it cannot be created (read-only filesystem, permissions).
Status ensureDirectory(const std::filesystem::path& directory);

// The prefix every temporary sibling carries.
inline constexpr std::string_view kTemporaryPrefix = ".tmp-";

// A directory under construction. Files written into path() become visible under `target`
// together when commit() succeeds; a StagingDirectory destroyed uncommitted removes itself.
// create() makes the target's missing parent directories.
class StagingDirectory {
 public:
  static Result<StagingDirectory> create(const std::filesystem::path& target);
  StagingDirectory(StagingDirectory&& other) noexcept;
  StagingDirectory& operator=(StagingDirectory&&) = delete;
  StagingDirectory(const StagingDirectory&) = delete;
  ~StagingDirectory();

  const std::filesystem::path& path() const { return staging_; }
  // commit() replaces an existing target only if this accepts it (checked on the swapped-out
  // directory, after the atomic exchange, and undone if refused). Default: anything.
  void setReplaceCheck(std::function<bool(const std::filesystem::path&)> may_replace) {
    may_replace_ = std::move(may_replace);
  }
  // commit() fails instead of replacing an existing target, which is never touched (not even
  // swapped out for an instant).
  void forbidReplacing() { replacing_forbidden_ = true; }
  // fsyncs the directory, renames it to the target (atomically exchanging an existing target,
  // which is then removed) and fsyncs the parent.
  Status commit();

 private:
  StagingDirectory(std::filesystem::path staging, std::filesystem::path target)
      : staging_(std::move(staging)), target_(std::move(target)) {}
  std::filesystem::path staging_;
  std::filesystem::path target_;
  std::function<bool(const std::filesystem::path&)> may_replace_;
  bool replacing_forbidden_ = false;
  bool committed_ = false;
};

// Removes ".tmp-*" entries left in directory by an interrupted writer, those not modified for
// at least `min_age` (a younger one may belong to a writer still running) and, when `names`
// is not empty, only temporaries of those files (".tmp-<name>-*"); returns how many.
std::size_t removeStaleTemporaries(const std::filesystem::path& directory,
                                   std::chrono::seconds min_age = std::chrono::seconds(0),
                                   std::span<const std::string_view> names = {});

}  // namespace glarecam
