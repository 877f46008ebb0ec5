#include "core/atomic_file.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "core/unique_fd.h"

namespace glarecam {
namespace fs = std::filesystem;

namespace {

std::unexpected<Error> systemError(const fs::path& path, const char* what) {
  int err = errno;
  std::string message = path.string() + ": " + what + ": " + std::strerror(err);
  if (err == ENOSPC) message += " (disk full)";
  if (err == EROFS) message += " (read-only filesystem)";
  return ioError(message);
}

Status writeAll(int fd, const fs::path& path, std::span<const std::byte> bytes) {
  while (!bytes.empty()) {
    ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return systemError(path, "cannot write");
    }
    bytes = bytes.subspan(static_cast<std::size_t>(written));
  }
  return {};
}

fs::path temporarySibling(const fs::path& target) {
  return target.parent_path() /
         (std::string(kTemporaryPrefix) + target.filename().string() + "-XXXXXX");
}

fs::path parentOf(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

}  // namespace

Status fsyncPath(const fs::path& path) {
  UniqueFd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) return systemError(path, "cannot open for fsync");
  if (::fsync(fd.get()) != 0) return systemError(path, "fsync failed");
  return {};
}

Status writeFileDurable(const fs::path& path, std::span<const std::byte> bytes) {
  UniqueFd fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) return systemError(path, "cannot create");
  if (auto status = writeAll(fd.get(), path, bytes); !status) return status;
  if (::fsync(fd.get()) != 0) return systemError(path, "fsync failed");
  if (fd.close() != 0) return systemError(path, "close failed");
  return {};
}

Result<fs::path> createTemporarySibling(const fs::path& target) {
  std::string temp = temporarySibling(target).string();
  UniqueFd fd(::mkostemp(temp.data(), O_CLOEXEC));
  if (fd.get() < 0) return systemError(target, "cannot create temporary file");
  if (::fchmod(fd.get(), 0644) != 0) {
    auto error = systemError(temp, "cannot chmod");
    ::unlink(temp.c_str());
    return error;
  }
  return fs::path(temp);
}

Status commitTemporary(const fs::path& temp, const fs::path& target) {
  auto fail_with = [&](Status status) {
    ::unlink(temp.c_str());
    return status;
  };
  if (auto status = fsyncPath(temp); !status) return fail_with(status);
  if (::rename(temp.c_str(), target.c_str()) != 0)
    return fail_with(systemError(target, "cannot rename into place"));
  return fsyncPath(parentOf(target));
}

Status writeFileAtomic(const fs::path& path, std::span<const std::byte> bytes) {
  fs::path temp;
  GLARECAM_ASSIGN(temp, createTemporarySibling(path));
  if (auto status = writeFileDurable(temp, bytes); !status) {
    ::unlink(temp.c_str());
    return status;
  }
  return commitTemporary(temp, path);
}

Status writeFileAtomic(const fs::path& path, std::string_view text) {
  return writeFileAtomic(path, std::as_bytes(std::span(text.data(), text.size())));
}

Result<StagingDirectory> StagingDirectory::create(const fs::path& target) {
  // Like mkdir -p for the parents: `--out runs/2026-11-26/alpha-60` should just work.
  std::error_code ec;
  if (const fs::path parent = target.parent_path(); !parent.empty())
    fs::create_directories(parent, ec);
  if (ec) return ioError(target.parent_path().string() + ": cannot create: " + ec.message());
  std::string staging = temporarySibling(target).string();
  if (::mkdtemp(staging.data()) == nullptr)
    return systemError(target, "cannot create staging directory");
  // mkdtemp creates 0700; a stack is an ordinary shared directory once visible.
  if (::chmod(staging.c_str(), 0755) != 0) {
    auto error = systemError(staging, "cannot chmod staging directory");
    ::rmdir(staging.c_str());
    return error;
  }
  return StagingDirectory(fs::path(staging), target);
}

StagingDirectory::StagingDirectory(StagingDirectory&& other) noexcept
    : staging_(std::move(other.staging_)),
      target_(std::move(other.target_)),
      may_replace_(std::move(other.may_replace_)),
      replacing_forbidden_(other.replacing_forbidden_),
      committed_(other.committed_) {
  other.committed_ = true;  // the moved-from object no longer owns the directory
}

StagingDirectory::~StagingDirectory() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

Status StagingDirectory::commit() {
  if (committed_)
    return fail(ErrorCode::kInternal, target_.string() + ": staging directory already committed");
  if (auto status = fsyncPath(staging_); !status) return status;
  std::error_code ec;
  const bool replacing = !replacing_forbidden_ && fs::exists(target_, ec);
  if (!replacing) {
    // RENAME_NOREPLACE: a concurrent writer that got there first is not silently overwritten.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_NOREPLACE) != 0) {
      return systemError(target_, "cannot rename staging directory into place");
    }
  } else {
    // Swap the complete new directory with the old one in one step, then drop the old one, but
    // only if what was swapped out may be replaced: checked after the swap, so nothing put at
    // the target since any earlier check can be deleted (it is swapped back instead).
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
      return systemError(target_, "cannot exchange staging directory with existing one");
    }
    if (may_replace_ && !may_replace_(staging_)) {
      ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE);
      return badInput(target_.string() +
                      ": changed into something that may not be replaced; left untouched");
    }
  }
  committed_ = true;
  // Make the new name durable before the old contents go away.
  Status synced = fsyncPath(parentOf(target_));
  if (replacing) fs::remove_all(staging_, ec);
  return synced;
}

namespace {

bool isTemporaryOf(const std::string& filename, std::span<const std::string_view> names) {
  if (!filename.starts_with(kTemporaryPrefix)) return false;
  if (names.empty()) return true;
  return std::any_of(names.begin(), names.end(), [&](std::string_view name) {
    return filename.starts_with(std::string(kTemporaryPrefix) + std::string(name) + "-");
  });
}

}  // namespace

std::size_t removeStaleTemporaries(const fs::path& directory, std::chrono::seconds min_age,
                                   std::span<const std::string_view> names) {
  std::size_t removed = 0;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    if (!isTemporaryOf(entry.path().filename().string(), names)) continue;
    std::error_code time_ec;
    const auto modified = fs::last_write_time(entry.path(), time_ec);
    if (time_ec || now - modified < min_age) continue;
    std::error_code remove_ec;
    fs::remove_all(entry.path(), remove_ec);
    if (!remove_ec) ++removed;
  }
  return removed;
}

Status ensureDirectory(const fs::path& directory) {
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    return badInput(directory.string() + ": exists and is not a directory");
  fs::create_directories(directory, ec);
  if (ec) return ioError(directory.string() + ": cannot create the directory: " + ec.message());
  return {};
}

}  // namespace glarecam
