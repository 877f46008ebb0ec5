#include "daemon/result_brief.h"

#include <nlohmann/json.hpp>
#include <system_error>

#include "core/stack_manifest.h"
#include "daemon/day_products.h"
#include "pipeline/process_stack.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

ResultBrief resultBrief(const nlohmann::json& result) {
  using Pointer = nlohmann::json::json_pointer;
  const auto number = [&result](const char* pointer) -> std::optional<double> {
    const nlohmann::json value = result.value(Pointer(pointer), nlohmann::json());
    return value.is_number() ? std::optional(value.get<double>()) : std::nullopt;
  };
  ResultBrief brief{.alpha_deg = number("/alpha_deg"),
                    .lmax_cd_m2 = number("/luminance/max_cd_m2").value_or(0),
                    .limit_cd_m2 = number("/limit/limit_cd_m2")};
  if (result.value(Pointer("/luminance/max_is_lower_bound"), false)) brief.lmax_bound = "lower";
  if (result.value(Pointer("/luminance/max_is_upper_bound"), false)) brief.lmax_bound = "upper";
  if (const auto glare = result.value(Pointer("/glare"), nlohmann::json()); glare.is_boolean())
    brief.glare = glare.get<bool>();
  return brief;
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
  const auto result = readJsonFile((*newest / pipeline::kResultFileName).string());
  if (!result || !result->is_object()) return std::nullopt;
  return LastResult{
      .stack_id = newest->filename().string(), .directory = *newest, .brief = resultBrief(*result)};
}

}  // namespace glarecam::daemon
