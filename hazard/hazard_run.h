// `glarecam hazard` as one call: read and validate the scene and every profile (nothing is
// written when any input is wrong), compute the year (hazard_calculation.h) with progress on
// stderr, and write the outputs (hazard_report.h) into the output directory; then, when asked,
// the PDF report (hazard_pdf.h). A report that cannot be written is a kIo error naming its file
// (the other outputs are written by then).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/error.h"
#include "hazard/civil_time.h"
#include "hazard/hazard_calculation.h"
#include "hazard/hazard_geojson.h"
#include "hazard/screening.h"

namespace glarecam::hazard {

struct HazardRunOptions {
  std::filesystem::path scene;
  std::optional<std::filesystem::path> profile;  // for arrays without their own
  std::filesystem::path out;
  HazardOptions hazard;
  DaylightSaving daylight_saving = DaylightSaving::kNone;  // civil clock times beside standard
  std::optional<std::filesystem::path> report;  // the PDF report (hazard_pdf.h), if wanted
  // The sun was not asked for (`--sun` not given): hazard.sun (the clear sky) where every profile
  // has a referred contour ladder, else the reference sun, with a warning naming the profile
  // (a profile from a table, or of an earlier glarecam). Asked for, a profile without a ladder
  // is refused.
  bool sun_by_default = false;
  bool show_progress = true;
  // Screening (screening.h): a row per receptor point instead of charts and a report; with a
  // shard, only that shard's shard.json.
  bool screen = false;
  std::optional<ShardSpec> shard;

  Status validate() const;
};

struct HazardRunSummary {
  nlohmann::json document;  // hazard.json as written
  std::string table;        // the short table for stdout
  std::vector<std::string> warnings;
};

// A report path that can never be written, refused before anything is computed (kBadInput): an
// existing directory, or a path under a file. Missing directories on the way are made.
Status checkReportPath(const std::filesystem::path& report);

Result<HazardRunSummary> runHazard(const HazardRunOptions& options);

// `glarecam hazard merge`: the shard directories (or shard.json files) combined into the outputs
// one screening writes, into `out`. The scene is read again from where the shards say it is, or
// from `scene` when given (its SHA-256 must match theirs).
struct HazardMergeOptions {
  std::vector<std::filesystem::path> shards;
  std::filesystem::path out;
  std::optional<std::filesystem::path> scene;
  Status validate() const;
};
Result<HazardRunSummary> runHazardMerge(const HazardMergeOptions& options);

}  // namespace glarecam::hazard
