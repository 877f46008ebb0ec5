// What the status page says of a processed stack, from its result.json (glarecam.result/1): the
// brief the stack worker reports as it writes a result, and the newest result already on disk,
// for a glarecamd that starts again.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "pipeline/result.h"

namespace glarecam::daemon {

struct ResultBrief {
  std::optional<double> alpha_deg{};
  double lmax_cd_m2 = 0;
  std::string lmax_bound{};  // "lower", "upper" or empty: Lmax is a bound of a saturated frame
  std::optional<double> limit_cd_m2{};
  std::optional<bool> glare{};  // the verdict: Lmax above the limit (none without a limit)
};

// The last stack processed: its result directory (luminance.png is its Figure-9 picture) and
// what the status page says of it.
struct LastResult {
  std::string stack_id;
  std::filesystem::path directory;
  ResultBrief brief;
  // Retention pruned its images (or deleted it whole) since: the brief's numbers stay, the picture
  // is gone (retention.h).
  bool images_pruned = false;
};

// The brief of a result.
ResultBrief resultBrief(const pipeline::StackResult& result);

// The newest result under `results` (results/<id>/result.json: ids begin with their UTC time, so
// the greatest id is the newest; other names are skipped); nullopt when there is none, or the
// newest cannot be read (pipeline::readResult refuses it).
std::optional<LastResult> newestResult(const std::filesystem::path& results);

}  // namespace glarecam::daemon
