// Retention: what glarecamd deletes so that a rig left in a field for a season never stops for a
// full disk while a past day still has something to give ([output] keep_stacks_days,
// keep_results_days, max_use_gib; docs/operator.md "Retention").
//
// By age:
//   stacks/<id>/    once older than keep_stacks_days;
//   results/<id>/   once older than keep_results_days, and only after their stack;
//   days/<day>/     once older than keep_results_days (days go by age only).
//
// By value (max_use_gib set): while the output tree uses more than the budget, or the disk has
// less than the reserve free, the least valuable bytes of past days go first, tier by tier, each
// oldest first:
//   1. stacks of past days that have a complete result ("stack");
//   2. the images of past days' results whose stack is gone (the files result.json's `outputs`
//      names: luminance.exr, quality.exr, luminance.png): result.json stays, marked first with
//      outputs.pruned_at ("result images");
//   3. whole results of past days whose row is in their day's sweep.csv, their stack gone
//      ("result"): the day's table and sheets keep their numbers (day_products.h keeps the row of
//      a result that is gone).
// Every stack ever written thus keeps its numbers: its result.json, or a row in its day's table.
// When nothing of a past day may go, the shortfall names what stays and why; when today alone is
// over the limit, that the budget is smaller than one day's stacks, and how many stacks a day
// would fit (else what past days keep, and what that leaves for today).
//
// What is never deleted: a stack without a complete result (unprocessed, being processed) or
// whose processing failed (results/<id>.failed); anything of today (the site's solar day, as the
// day sheets count days) or whose day its name does not tell; anything glarecam did not make (a
// stack is recognised by its manifest, stack.json of schema glarecam.stack/1; a result by its
// result.json of schema glarecam.result/1, and of a result's files only those it names; a day by
// its name YYYY-MM-DD and its sweep.csv); anything outside the output root (symbolic links are not
// followed). Without any setting nothing is deleted. A directory is renamed to a hidden temporary
// first and then removed, so a deletion cut short leaves only a temporary that the next start
// removes, never half a stack. A result's images are removed only after result.json says so, so a
// prune cut short leaves a result that says "pruned" with some images still there, which the next
// start removes (finishCutShortPrunes); never a result.json naming a missing image without saying
// so.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/time.h"
#include "daemon/storage/disk_space.h"
#include "daemon/storage/output_tree.h"
#include "pipeline/result.h"

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

// RetentionDeletion::kind, by tier.
inline constexpr const char* kDeletedStack = "stack";
inline constexpr const char* kDeletedResultImages = "result images";
inline constexpr const char* kDeletedResult = "result";
inline constexpr const char* kDeletedDay = "day";

struct RetentionDeletion {
  std::string kind;  // kDeletedStack, kDeletedResultImages, kDeletedResult or kDeletedDay
  std::string name;  // the stack id or the day
  std::uint64_t bytes = 0;
  std::string reason;  // "older than 30 days", "over the 2.0 GiB budget", "below the reserve"
};

struct RetentionSummary {
  std::vector<RetentionDeletion> deleted{};
  std::uint64_t freed_bytes = 0;
  std::uint64_t used_bytes = 0;  // by the output tree after the deletions (with a budget only)
  // Why the space asked for could not be freed ("3.1 GiB used, over the 2.0 GiB budget; nothing
  // more may go (stacks kept: 4 unprocessed, 12 of today)"; "…; today's 40 stacks and their
  // results take 190.0 MiB, more than the budget leaves for a day (120.0 MiB): about 25 stacks a
  // day fit"), or empty.
  std::string shortfall{};
  // Of what the shortfall names: today's stacks and their results alone do not fit.
  bool day_overflows = false;
  std::vector<std::string> errors{};  // deletions that failed (the entry is left as it was)
};

struct RetentionContext {
  UtcTime now{};                          // the daemon's clock
  std::optional<double> longitude_deg{};  // the site's: days as day_products.h counts them
  std::optional<DiskState> disk{};        // the disk now, for the reserve
  std::uint64_t reserve_bytes = 0;
};

// Applies the policy to the output tree once: a prune cut short is finished, then the age rules,
// then the space rule's tiers. Never throws.
RetentionSummary applyRetention(const OutputTree& tree, const RetentionPolicy& policy,
                                const RetentionContext& context);

// At start: finishes every prune cut short (a result marked pruned that still holds images), what
// a power cut in the middle of tier 2 leaves. Whatever the policy and the clock: the decision was
// taken and written before the cut. Deletions of kind kDeletedResultImages.
RetentionSummary finishCutShortPrunes(const OutputTree& tree, UtcTime now);

// Tier 2 for one result directory: marks its result.json pruned at `now` (atomically; kept when
// already marked) and then removes the files its `outputs` names. kBadInput when result.json is
// missing or not a readable glarecam result (nothing is touched), kIo when it cannot be
// rewritten; a file that cannot be removed is an error in the outcome, the others still go.
struct PrunedImages {
  std::uint64_t bytes = 0;          // removed
  std::vector<std::string> errors;  // files that could not be removed
};
Result<PrunedImages> pruneResultImages(const std::filesystem::path& directory, UtcTime now);

// The bytes of the images a result directory still holds (the files its result.json names).
std::uint64_t resultImageBytes(const std::filesystem::path& directory,
                               const pipeline::ResultOutputs& outputs);

}  // namespace glarecam::daemon
