#include "daemon/storage/retention.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "core/atomic_file.h"
#include "core/json.h"
#include "core/stack_io.h"
#include "core/time.h"
#include "daemon/storage/day_products.h"
#include "pipeline/process_stack.h"
#include "pipeline/result.h"
#include "pipeline/sweep.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;

// "2026-06-21" as a day, or nullopt for anything else (a directory of another name).
std::optional<UtcDay> parseDay(const std::string& text) {
  const auto day = parseIsoDay(text);
  return day ? std::optional(*day) : std::nullopt;
}

// The solar day of the stack (or its result) named `id`, or nullopt when its name tells none.
std::optional<std::chrono::sys_days> idDay(const std::string& id,
                                           std::optional<double> longitude_deg) {
  const std::optional<std::string> day = stackDay(id, longitude_deg);
  return day ? parseDay(*day) : std::nullopt;
}

bool isRealDirectory(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(fs::symlink_status(path, error));
}

// The bytes of the regular files under `path`, symbolic links not followed.
std::uint64_t treeBytes(const fs::path& path) {
  std::error_code error;
  std::uint64_t bytes = 0;
  const auto status = fs::symlink_status(path, error);
  if (fs::is_regular_file(status)) return fs::file_size(path, error);
  if (!fs::is_directory(status)) return 0;
  for (fs::recursive_directory_iterator it(path, error), end; !error && it != end;
       it.increment(error)) {
    if (it->is_regular_file(error) && !it->is_symlink(error)) {
      const std::uintmax_t size = it->file_size(error);
      if (!error) bytes += size;
      error.clear();
    }
  }
  return bytes;
}

bool isResultDirectory(const fs::path& path) {
  std::error_code error;
  if (!isRealDirectory(path) || !fs::is_regular_file(path / pipeline::kResultFileName, error))
    return false;
  const auto result = readJsonFile(path / pipeline::kResultFileName);
  return result && pipeline::hasResultSchema(*result);
}

bool isDayDirectory(const fs::path& path) {
  std::error_code error;
  return isRealDirectory(path) && parseDay(path.filename().string()) &&
         fs::is_regular_file(path / pipeline::kSweepTableFileName, error);
}

// Renames `path` to a hidden temporary beside it (what removeLeftovers() clears at the next start
// if this is cut short), then removes that.
Status removeDirectory(const fs::path& path) {
  const fs::path doomed =
      path.parent_path() / (std::string(kTemporaryPrefix) + "deleted-" + path.filename().string());
  std::error_code error;
  fs::remove_all(doomed, error);  // an earlier deletion cut short
  fs::rename(path, doomed, error);
  if (error) return fail(ErrorCode::kIo, path.string() + ": cannot delete: " + error.message());
  fs::remove_all(doomed, error);
  if (error) return fail(ErrorCode::kIo, doomed.string() + ": cannot delete: " + error.message());
  return {};
}

// The entries of `directory` by name (names that begin with a time or a day: oldest first).
std::vector<fs::path> sortedEntries(const fs::path& directory) {
  std::error_code error;
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(directory, error))
    entries.push_back(entry.path());
  std::ranges::sort(entries);
  return entries;
}

struct Candidate {
  std::string name;
  fs::path path;
  std::chrono::sys_days day;
};

// Why some stacks may not go, for a shortfall: "4 unprocessed, 12 of today".
struct Withheld {
  std::size_t unprocessed = 0, failed = 0, today = 0, undated = 0;
  std::string describe() const {
    std::vector<std::string> parts;
    if (unprocessed) parts.push_back(fmt::format("{} unprocessed", unprocessed));
    if (failed) parts.push_back(fmt::format("{} failed", failed));
    if (today) parts.push_back(fmt::format("{} of today", today));
    if (undated) parts.push_back(fmt::format("{} undated", undated));
    if (parts.empty()) return "no processed stack before today left";
    return fmt::format("stacks kept: {}", fmt::join(parts, ", "));
  }
};

}  // namespace

Status RetentionPolicy::validate() const {
  const auto days = [](const char* key, const std::optional<int>& value) -> Status {
    if (value && (*value < 1 || *value > kMaxKeepDays))
      return badInput(fmt::format("{}: must be between 1 and {} days", key, kMaxKeepDays));
    return {};
  };
  GLARECAM_CHECK(days("keep_stacks_days", keep_stacks_days));
  GLARECAM_CHECK(days("keep_results_days", keep_results_days));
  if (keep_stacks_days && keep_results_days && *keep_results_days < *keep_stacks_days)
    return badInput(
        "keep_results_days: must be at least keep_stacks_days (a result goes only after "
        "its stack)");
  if (max_use_bytes && *max_use_bytes == 0) return badInput("max_use_gib: must be positive");
  return {};
}

RetentionSummary applyRetention(const OutputTree& tree, const RetentionPolicy& policy,
                                const RetentionContext& context) {
  RetentionSummary summary;
  if (!policy.enabled()) return summary;
  const std::optional<std::chrono::sys_days> today =
      parseDay(solarDay(context.now, context.longitude_deg));
  if (!today) {  // a clock beyond the year 9999: no age can be told, nothing goes
    summary.errors.push_back("the clock's day cannot be told; nothing deleted");
    return summary;
  }
  const auto ageDays = [&](std::chrono::sys_days day) { return (*today - day).count(); };
  const auto remove = [&](const std::string& kind, const std::string& name, const fs::path& path,
                          const std::string& reason) {
    const std::uint64_t bytes = treeBytes(path);
    const Status removed = removeDirectory(path);
    if (!removed) {
      summary.errors.push_back(removed.error().message);
      return false;
    }
    summary.deleted.push_back({kind, name, bytes, reason});
    summary.freed_bytes += bytes;
    return true;
  };

  // Stacks that may go: glarecam's, processed to a complete result, of a day before today.
  std::vector<Candidate> stacks;
  Withheld withheld;
  std::error_code error;
  for (const fs::path& entry : sortedEntries(tree.stacks())) {
    const std::string id = entry.filename().string();
    if (id.starts_with(kTemporaryPrefix) || !isStackDirectory(entry)) continue;
    const std::optional<std::chrono::sys_days> day = idDay(id, context.longitude_deg);
    if (!day) {
      ++withheld.undated;
    } else if (*day >= *today) {
      ++withheld.today;
    } else if (fs::exists(tree.results() / (id + kFailedSuffix), error)) {
      ++withheld.failed;
    } else if (!isResultDirectory(tree.results() / id)) {
      ++withheld.unprocessed;
    } else {
      stacks.push_back({id, entry, *day});
    }
  }

  if (policy.keep_stacks_days) {
    const std::string reason = fmt::format("older than {} days", *policy.keep_stacks_days);
    std::erase_if(stacks, [&](const Candidate& stack) {
      return ageDays(stack.day) >= *policy.keep_stacks_days &&
             remove("stack", stack.name, stack.path, reason);
    });
  }
  if (policy.keep_results_days) {
    const int keep = *policy.keep_results_days;
    const std::string reason = fmt::format("older than {} days", keep);
    for (const fs::path& entry : sortedEntries(tree.results())) {
      const std::string id = entry.filename().string();
      const std::optional<std::chrono::sys_days> day = idDay(id, context.longitude_deg);
      std::error_code missing;
      if (!day || ageDays(*day) < keep || !isResultDirectory(entry) ||
          fs::exists(fs::symlink_status(tree.stacks() / id, missing)))
        continue;
      remove("result", id, entry, reason);
    }
    for (const fs::path& entry : sortedEntries(tree.days())) {
      const std::string day = entry.filename().string();
      if (!isDayDirectory(entry) || ageDays(*parseDay(day)) < keep) continue;
      remove("day", day, entry, reason);
    }
  }

  if (!policy.max_use_bytes) return summary;
  summary.used_bytes =
      treeBytes(tree.stacks()) + treeBytes(tree.results()) + treeBytes(tree.days());
  // The space rule: the oldest stacks that may go, until the tree is within its budget and the
  // disk above its reserve.
  const std::uint64_t budget = *policy.max_use_bytes;
  const auto overBudget = [&] { return summary.used_bytes > budget; };
  const std::uint64_t free_before = context.disk ? context.disk->free_bytes : 0;
  const auto belowReserve = [&] {  // the age rules' deletions count: the probe came before them
    return context.disk && free_before + summary.freed_bytes < context.reserve_bytes;
  };
  const std::string over_reason = fmt::format("over the {} budget", formatBytes(budget));
  const std::string reserve_reason =
      fmt::format("below the {} reserve", formatBytes(context.reserve_bytes));
  for (const Candidate& stack : stacks) {
    if (!overBudget() && !belowReserve()) break;
    const std::string& reason = overBudget() ? over_reason : reserve_reason;
    const std::uint64_t freed = summary.freed_bytes;
    if (remove("stack", stack.name, stack.path, reason))
      summary.used_bytes -= std::min(summary.used_bytes, summary.freed_bytes - freed);
  }
  if (overBudget()) {
    summary.shortfall =
        fmt::format("{} used, over the {} budget; nothing more may go ({})",
                    formatBytes(summary.used_bytes), formatBytes(budget), withheld.describe());
  } else if (belowReserve()) {
    summary.shortfall = fmt::format("{} free, below the {} reserve; nothing more may go ({})",
                                    formatBytes(free_before + summary.freed_bytes),
                                    formatBytes(context.reserve_bytes), withheld.describe());
  }
  return summary;
}

}  // namespace glarecam::daemon
