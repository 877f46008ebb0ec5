#include "daemon/status/result_brief.h"

#include <system_error>

#include "daemon/storage/day_products.h"
#include "pipeline/process_stack.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

ResultBrief resultBrief(const pipeline::StackResult& result) {
  const pipeline::ResultLuminance& luminance = result.luminance;
  return {.alpha_deg = result.alpha_deg,
          .lmax_cd_m2 = luminance.max_cd_m2,
          .lmax_bound = luminance.isLowerBound()   ? "lower"
                        : luminance.isUpperBound() ? "upper"
                                                   : "",
          .limit_cd_m2 = result.limit.limit_cd_m2,
          .glare = result.glare};
}

std::optional<LastResult> newestResult(const fs::path& results) {
  std::error_code error;
  std::optional<fs::path> newest;
  for (fs::directory_iterator it(results, error), end; !error && it != end; it.increment(error)) {
    const fs::path& path = it->path();
    // Only stacks' ids, which begin with their time (a staging directory, a name of another
    // tool's would sort above every time stamp and stay "newest" for good).
    if (!stackDay(path.filename().string(), std::nullopt)) continue;
    std::error_code file_error;
    if (!fs::is_regular_file(path / pipeline::kResultFileName, file_error)) continue;
    if (!newest || path.filename() > newest->filename()) newest = path;
  }
  if (!newest) return std::nullopt;
  const auto result = pipeline::readResult(*newest / pipeline::kResultFileName);
  if (!result) return std::nullopt;
  return LastResult{.stack_id = newest->filename().string(),
                    .directory = *newest,
                    .brief = resultBrief(*result),
                    .images_pruned = result->outputs.pruned()};
}

}  // namespace glarecam::daemon
