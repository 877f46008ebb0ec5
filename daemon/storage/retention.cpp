#include "daemon/storage/retention.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
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

// A file name `outputs` gives that is a plain name in its directory (never a path out of it).
bool isPlainName(const std::string& name) {
  const fs::path path(name);
  return !name.empty() && path.filename() == path && name != "." && name != "..";
}

// The result.json of a glarecam result directory, read, or nullopt.
std::optional<pipeline::StackResult> readResultOf(const fs::path& directory) {
  if (!isRealDirectory(directory)) return std::nullopt;
  auto result = pipeline::readResult(directory / pipeline::kResultFileName);
  return result ? std::optional(std::move(*result)) : std::nullopt;
}

// Whether a result directory holds nothing but its result.json (its images pruned, or none).
bool holdsOnlyItsDocument(const fs::path& directory) {
  std::error_code error;
  for (fs::directory_iterator it(directory, error), end; !error && it != end; it.increment(error))
    if (it->path().filename() != pipeline::kResultFileName) return false;
  return true;
}

// The stack ids with a row in days/<day>/sweep.csv, read once a day.
class DayRows {
 public:
  explicit DayRows(fs::path days) : days_(std::move(days)) {}
  bool has(const std::string& day, const std::string& id) {
    auto [it, fresh] = ids_.try_emplace(day);
    if (fresh) {
      const auto table = pipeline::readSweepTable(days_ / day / pipeline::kSweepTableFileName);
      if (table)
        for (const pipeline::SweepRow& row : table->rows) it->second.insert(row.stack_id);
    }
    return it->second.contains(id);
  }

 private:
  fs::path days_;
  std::map<std::string, std::set<std::string>> ids_;
};

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

// Why some stacks and results may not go, for a shortfall: "stacks kept: 4 unprocessed, 12 of
// today; results kept: 3 not in their day's sweep.csv".
struct Withheld {
  std::size_t unprocessed = 0, failed = 0, today = 0, undated = 0;
  std::size_t results_without_row = 0, results_with_stack = 0;
  std::string describe() const {
    std::vector<std::string> stacks, results;
    if (unprocessed) stacks.push_back(fmt::format("{} unprocessed", unprocessed));
    if (failed) stacks.push_back(fmt::format("{} failed", failed));
    if (today) stacks.push_back(fmt::format("{} of today", today));
    if (undated) stacks.push_back(fmt::format("{} undated", undated));
    if (results_without_row)
      results.push_back(fmt::format("{} not in their day's sweep.csv", results_without_row));
    if (results_with_stack)
      results.push_back(fmt::format("{} with their stack", results_with_stack));
    std::vector<std::string> parts;
    if (!stacks.empty()) parts.push_back(fmt::format("stacks kept: {}", fmt::join(stacks, ", ")));
    if (!results.empty())
      parts.push_back(fmt::format("results kept: {}", fmt::join(results, ", ")));
    if (parts.empty()) return "nothing of a past day left";
    return fmt::format("{}", fmt::join(parts, "; "));
  }
};

// A past day's result that the space rule may reduce: its images (tier 2), then itself (tier 3).
struct ResultCandidate {
  std::string id;
  fs::path path;
  std::chrono::sys_days day;
  std::uint64_t image_bytes = 0;  // still on disk
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
             remove(kDeletedStack, stack.name, stack.path, reason);
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
      remove(kDeletedResult, id, entry, reason);
    }
    for (const fs::path& entry : sortedEntries(tree.days())) {
      const std::string day = entry.filename().string();
      if (!isDayDirectory(entry) || ageDays(*parseDay(day)) < keep) continue;
      remove(kDeletedDay, day, entry, reason);
    }
  }

  if (!policy.max_use_bytes) return summary;
  summary.used_bytes =
      treeBytes(tree.stacks()) + treeBytes(tree.results()) + treeBytes(tree.days());
  // The space rule: the least valuable bytes of past days, tier by tier, oldest first, until the
  // tree is within its budget and the disk above its reserve.
  const std::uint64_t budget = *policy.max_use_bytes;
  const auto overBudget = [&] { return summary.used_bytes > budget; };
  const std::uint64_t free_before = context.disk ? context.disk->free_bytes : 0;
  const auto belowReserve = [&] {  // the age rules' deletions count: the probe came before them
    return context.disk && free_before + summary.freed_bytes < context.reserve_bytes;
  };
  const auto pressed = [&] { return overBudget() || belowReserve(); };
  const std::string over_reason = fmt::format("over the {} budget", formatBytes(budget));
  const std::string reserve_reason =
      fmt::format("below the {} reserve", formatBytes(context.reserve_bytes));
  const auto reason = [&] { return overBudget() ? over_reason : reserve_reason; };
  const auto used = [&](std::uint64_t freed_before) {
    summary.used_bytes -= std::min(summary.used_bytes, summary.freed_bytes - freed_before);
  };

  // 1. Stacks with a complete result.
  for (const Candidate& stack : stacks) {
    if (!pressed()) break;
    const std::uint64_t freed = summary.freed_bytes;
    if (remove(kDeletedStack, stack.name, stack.path, reason())) used(freed);
  }

  // 2. and 3. Results of past days: their images, then (their row in the day's table, their stack
  // gone) themselves. Listed only when the stacks did not free enough.
  std::vector<ResultCandidate> results;
  if (pressed()) {
    for (const fs::path& entry : sortedEntries(tree.results())) {
      const std::string id = entry.filename().string();
      const std::optional<std::chrono::sys_days> day = idDay(id, context.longitude_deg);
      if (id.starts_with(kTemporaryPrefix) || !day || *day >= *today || !isRealDirectory(entry))
        continue;
      // A result whose stack is still there (processed after tier 1 listed the stacks, or a
      // stack that could not be deleted): the stack goes first, at a later pass.
      std::error_code missing;
      if (fs::exists(fs::symlink_status(tree.stacks() / id, missing))) {
        ++withheld.results_with_stack;
        continue;
      }
      results.push_back({id, entry, *day});
    }
  }
  for (ResultCandidate& result : results) {
    if (!pressed()) break;
    if (holdsOnlyItsDocument(result.path)) continue;  // pruned already: not read again
    const std::optional<pipeline::StackResult> read = readResultOf(result.path);
    if (!read) continue;  // not glarecam's, or being written
    result.image_bytes = resultImageBytes(result.path, read->outputs);
    if (result.image_bytes == 0) continue;
    const std::uint64_t freed = summary.freed_bytes;
    const auto pruned = pruneResultImages(result.path, context.now);
    if (!pruned) {
      summary.errors.push_back(pruned.error().message);
      continue;
    }
    for (const std::string& error : pruned->errors) summary.errors.push_back(error);
    if (pruned->bytes == 0) continue;
    summary.deleted.push_back({kDeletedResultImages, result.id, pruned->bytes, reason()});
    summary.freed_bytes += pruned->bytes;
    used(freed);
  }
  DayRows rows(tree.days());
  for (const ResultCandidate& result : results) {
    if (!pressed()) break;
    if (!isResultDirectory(result.path)) continue;
    if (!rows.has(formatIsoDay(result.day), result.id)) {
      ++withheld.results_without_row;
      continue;
    }
    const std::uint64_t freed = summary.freed_bytes;
    if (remove(kDeletedResult, result.id, result.path, reason())) used(freed);
  }

  if (!pressed()) return summary;
  // Nothing more of a past day may go. Is it today that does not fit?
  std::uint64_t today_bytes = 0;
  for (const fs::path& directory : {tree.stacks(), tree.results()})
    for (const fs::path& entry : sortedEntries(directory)) {
      const std::optional<std::chrono::sys_days> day =
          idDay(entry.filename().string(), context.longitude_deg);
      if (day && *day >= *today) today_bytes += treeBytes(entry);
    }
  const std::uint64_t free_now = free_before + summary.freed_bytes;
  // What the tree may hold: the budget, or what the disk holds above its reserve.
  const std::uint64_t limit =
      overBudget() ? budget
                   : summary.used_bytes + free_now -
                         std::min(free_now + summary.used_bytes, context.reserve_bytes);
  const std::uint64_t kept_before_today =
      summary.used_bytes - std::min(summary.used_bytes, today_bytes);
  const std::uint64_t days_bytes = treeBytes(tree.days());
  const std::string what = overBudget()
                               ? fmt::format("{} used, over the {} budget",
                                             formatBytes(summary.used_bytes), formatBytes(budget))
                               : fmt::format("{} free, below the {} reserve", formatBytes(free_now),
                                             formatBytes(context.reserve_bytes));
  summary.shortfall = fmt::format(
      "{}; nothing more may go ({}; day directories {}, which go by "
      "age only)",
      what, withheld.describe(), formatBytes(days_bytes));
  if (withheld.today == 0 || today_bytes == 0) return summary;
  const double per_stack = double(today_bytes) / double(withheld.today);
  if (today_bytes > limit) {
    // Today alone does not fit, however little the past keeps.
    summary.day_overflows = true;
    summary.shortfall += fmt::format(
        "; the budget is smaller than one day's stacks: today's {} stacks and their results take "
        "{}, more than all of the {}: about {} stacks a day fit (raise max_use_gib or capture "
        "less often)",
        withheld.today, formatBytes(today_bytes), formatBytes(limit),
        static_cast<std::uint64_t>(double(limit) / per_stack));
  } else {
    // Today would fit alone: what the past keeps leaves it too little.
    const std::uint64_t leaves = limit - std::min(limit, kept_before_today);
    summary.shortfall += fmt::format(
        "; what past days keep ({}) leaves {} for today's {} stacks and their results ({}): "
        "about {} stacks a day fit (set keep_results_days, or raise max_use_gib)",
        formatBytes(kept_before_today), formatBytes(leaves), withheld.today,
        formatBytes(today_bytes), static_cast<std::uint64_t>(double(leaves) / per_stack));
  }
  return summary;
}

RetentionSummary finishCutShortPrunes(const OutputTree& tree, UtcTime now) {
  RetentionSummary summary;
  for (const fs::path& entry : sortedEntries(tree.results())) {
    const std::string id = entry.filename().string();
    if (id.starts_with(kTemporaryPrefix)) continue;
    const std::optional<pipeline::StackResult> read = readResultOf(entry);
    if (!read || !read->outputs.pruned() || resultImageBytes(entry, read->outputs) == 0) continue;
    const auto pruned = pruneResultImages(entry, now);
    if (!pruned) {
      summary.errors.push_back(pruned.error().message);
      continue;
    }
    for (const std::string& error : pruned->errors) summary.errors.push_back(error);
    if (pruned->bytes == 0) continue;
    summary.deleted.push_back(
        {kDeletedResultImages, id, pruned->bytes, "finishing a prune cut short"});
    summary.freed_bytes += pruned->bytes;
  }
  return summary;
}

std::uint64_t resultImageBytes(const fs::path& directory, const pipeline::ResultOutputs& outputs) {
  std::uint64_t bytes = 0;
  for (const std::string& name : outputs.files()) {
    std::error_code error;
    if (!isPlainName(name) || name == pipeline::kResultFileName) continue;
    const fs::path file = directory / name;
    if (fs::is_regular_file(fs::symlink_status(file, error))) {
      const std::uintmax_t size = fs::file_size(file, error);
      if (!error) bytes += size;
    }
  }
  return bytes;
}

Result<PrunedImages> pruneResultImages(const fs::path& directory, UtcTime now) {
  const fs::path file = directory / pipeline::kResultFileName;
  if (!isRealDirectory(directory)) return badInput(directory.string() + ": not a result directory");
  auto result = pipeline::readResult(file);
  if (!result) return std::unexpected(result.error());
  // result.json says so first: a prune cut short leaves a result that says "pruned".
  if (!result->outputs.pruned()) {
    result->outputs.pruned_at = formatIsoTime(std::chrono::floor<std::chrono::seconds>(now));
    GLARECAM_CHECK(writeFileAtomic(file, jsonText(pipeline::toJson(*result))));
  }
  PrunedImages pruned;
  for (const std::string& name : result->outputs.files()) {
    if (!isPlainName(name) || name == pipeline::kResultFileName) continue;
    const fs::path image = directory / name;
    std::error_code error;
    if (!fs::is_regular_file(fs::symlink_status(image, error))) continue;
    const std::uintmax_t size = fs::file_size(image, error);
    if (!fs::remove(image, error) || error) {
      pruned.errors.push_back(image.string() + ": cannot delete: " + error.message());
      continue;
    }
    pruned.bytes += size;
  }
  return pruned;
}

}  // namespace glarecam::daemon
