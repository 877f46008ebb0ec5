// Retention: what glarecamd deletes so that a rig left in a field for a season never stops for a
// full disk ([output] keep_stacks_days, keep_results_days, max_use_gib; docs/operator.md).
//
//   stacks/<id>/    deleted once older than keep_stacks_days, or, oldest first, while the output
//                   tree uses more than max_use_gib or (max_use_gib set) the disk has less than
//                   the reserve free;
//   results/<id>/   deleted once older than keep_results_days, and only after their stack;
//   days/<day>/     deleted once older than keep_results_days.
//
// What is never deleted: a stack without a complete result (unprocessed, being processed) or
// whose processing failed (results/<id>.failed); anything of today (the site's solar day, as the
// day sheets count days) or whose day its name does not tell; anything glarecam did not make (a
// stack is recognised by its manifest, stack.json of schema glarecam.stack/1; a result by its
// result.json of schema glarecam.result/1; a day by its name YYYY-MM-DD and its sweep.csv);
// anything outside the output root (symbolic links are not followed). Without any setting
// nothing is deleted. A directory is renamed to a hidden temporary first and then removed, so a
// deletion cut short leaves only a temporary that the next start removes, never half a stack.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/time.h"
#include "daemon/storage/disk_space.h"
#include "daemon/storage/output_tree.h"

namespace glarecam::daemon {

// Upper bound of the day settings: a century.
inline constexpr int kMaxKeepDays = 36500;

struct RetentionPolicy {
  std::optional<int> keep_stacks_days{};         // 1 … kMaxKeepDays
  std::optional<int> keep_results_days{};        // 1 … kMaxKeepDays, at least keep_stacks_days
  std::optional<std::uint64_t> max_use_bytes{};  // of stacks/, results/ and days/ together

  bool enabled() const { return keep_stacks_days || keep_results_days || max_use_bytes; }
  // kBadInput naming the setting that is out of range or inconsistent.
  Status validate() const;
};

struct RetentionDeletion {
  std::string kind;  // "stack", "result" or "day"
  std::string name;  // the stack id or the day
  std::uint64_t bytes = 0;
  std::string reason;  // "older than 30 days", "over the 2.0 GiB budget", "below the reserve"
};

struct RetentionSummary {
  std::vector<RetentionDeletion> deleted{};
  std::uint64_t freed_bytes = 0;
  std::uint64_t used_bytes = 0;  // by the output tree after the deletions (with a budget only)
  // Why the space asked for could not be freed ("3.1 GiB used, over the 2.0 GiB budget: nothing
  // more may go (4 stacks unprocessed, 12 of today)"), or empty.
  std::string shortfall{};
  std::vector<std::string> errors{};  // deletions that failed (the entry is left as it was)
};

struct RetentionContext {
  UtcTime now{};                          // the daemon's clock
  std::optional<double> longitude_deg{};  // the site's: days as day_products.h counts them
  std::optional<DiskState> disk{};        // the disk now, for the reserve
  std::uint64_t reserve_bytes = 0;
};

// Applies the policy to the output tree once: the age rules, then the space rule. Never throws.
RetentionSummary applyRetention(const OutputTree& tree, const RetentionPolicy& policy,
                                const RetentionContext& context);

}  // namespace glarecam::daemon
