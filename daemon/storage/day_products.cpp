#include "daemon/storage/day_products.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/json.h"
#include "core/time.h"
#include "pipeline/contour_table.h"
#include "pipeline/datasheet_publish.h"
#include "pipeline/glare_fits.h"
#include "pipeline/process_stack.h"
#include "pipeline/sweep.h"
#include "pipeline/sweep_table.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

namespace {

constexpr double kDegreesPerHour = 15.0;  // the Earth turns 360° in 24 h

// The rows (and ladders) the day's tables hold for stacks whose result retention deleted whole
// (retention.h, tier 3): their numbers live on only there, so a rebuild keeps them.
void keepRowsOfDeletedResults(const DayProductsOptions& options, const std::string& day,
                              pipeline::SweepTable& table, pipeline::ContourTable& contours) {
  const fs::path directory = options.root / kDaysDirectory / day;
  const fs::path results = options.root / kResultsDirectory;
  const auto gone = [&](const std::string& id) {
    std::error_code error;
    return !id.empty() && fs::path(id).filename() == fs::path(id) &&
           !fs::exists(fs::symlink_status(results / id, error));
  };
  std::error_code error;
  if (!fs::is_regular_file(directory / pipeline::kSweepTableFileName, error)) return;
  const auto old_table = pipeline::readSweepTable(directory / pipeline::kSweepTableFileName);
  if (!old_table) {  // a table of notes only, or one that was never ours: nothing to keep
    spdlog::debug("day {}: the earlier table keeps no rows: {}", day, old_table.error().message);
    return;
  }
  std::size_t kept = 0;
  for (const pipeline::SweepRow& row : old_table->rows)
    if (gone(row.stack_id)) {
      table.rows.push_back(row);
      ++kept;
    }
  if (kept == 0) return;
  const auto old_contours = pipeline::readContourTable(directory / pipeline::kContourTableFileName);
  if (!old_contours) return;  // the rows stay; their ladders are lost with the earlier file
  for (const pipeline::ContourRow& contour : old_contours->rows)
    if (gone(contour.stack_id)) contours.rows.push_back(contour);
}

// The rows of the day's processed stacks, with a note for each result that gives none, and
// their contour ladders into `contours`.
pipeline::SweepTable dayTable(const DayProductsOptions& options, const std::string& day,
                              pipeline::ContourTable& contours) {
  pipeline::SweepTable table;
  std::error_code error;
  const fs::path results = options.root / kResultsDirectory;
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(results, error)) entries.push_back(entry.path());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& entry : entries) {
    const std::string id = entry.filename().string();
    if (stackDay(id, options.longitude_deg) != day) continue;
    const fs::path result_file = entry / pipeline::kResultFileName;
    if (!fs::is_regular_file(result_file, error)) continue;  // being processed
    const auto result = pipeline::readResult(result_file);
    auto row = result ? pipeline::sweepRowFromResult(
                            *result, (options.root / kStacksDirectory / id).string())
                      : Result<pipeline::SweepRow>(std::unexpected(result.error()));
    if (!row) {
      table.notes.push_back(fmt::format("skipped {}: {}", id, row.error().message));
      continue;
    }
    table.rows.push_back(std::move(*row));
    for (pipeline::ContourRow& contour : pipeline::contourRowsFromResult(*result))
      contours.rows.push_back(std::move(contour));
  }
  keepRowsOfDeletedResults(options, day, table, contours);
  pipeline::sortByAlpha(table);
  return table;
}

}  // namespace

std::optional<std::string> stackDay(std::string_view stack_id,
                                    std::optional<double> longitude_deg) {
  const auto utc = parseStackStamp(stack_id);
  if (!utc) return std::nullopt;
  return solarDay(*utc, longitude_deg);
}

std::string solarDay(UtcTime utc, std::optional<double> longitude_deg) {
  const auto offset =
      std::chrono::seconds(std::lround(longitude_deg.value_or(0.0) / kDegreesPerHour * 3600.0));
  const std::chrono::year_month_day date{std::chrono::floor<std::chrono::days>(utc + offset)};
  return fmt::format("{:04}-{:02}-{:02}", int(date.year()), unsigned(date.month()),
                     unsigned(date.day()));
}

Result<DaySummary> updateDayProducts(const DayProductsOptions& options, const std::string& day) {
  DaySummary summary{.day = day, .directory = options.root / kDaysDirectory / day};
  pipeline::ContourTable contours;
  const pipeline::SweepTable table = dayTable(options, day, contours);
  summary.stacks = table.rows.size();
  GLARECAM_CHECK(ensureDirectory(summary.directory));
  GLARECAM_CHECK(writeFileAtomic(summary.directory / pipeline::kSweepTableFileName,
                                 pipeline::formatSweepTable(table)));
  GLARECAM_CHECK(writeFileAtomic(summary.directory / pipeline::kContourTableFileName,
                                 pipeline::formatContourTable(contours)));
  // A stack whose source illuminance could not be read (the instrument failed) stays in the
  // day's table, but the sheet is of one reference.
  std::string left_out;
  const pipeline::SweepTable sheet_table = pipeline::rowsOfOneReference(table, &left_out);
  if (!left_out.empty()) spdlog::warn("day {}: {}", day, left_out);
  pipeline::ContourTable sheet_contours;  // the ladders of the sheet's rows: the profile's
  for (const pipeline::ContourRow& contour : contours.rows)
    if (std::ranges::any_of(sheet_table.rows, [&](const pipeline::SweepRow& row) {
          return row.stack_id == contour.stack_id;
        }))
      sheet_contours.rows.push_back(contour);
  const auto fits = pipeline::fitSweep(sheet_table);
  if (!fits) {
    summary.detail =
        fmt::format("{} stacks; no data sheet yet: {}", summary.stacks, fits.error().message);
    return summary;
  }
  GLARECAM_CHECK(
      writeFileAtomic(summary.directory / kFitsFileName, jsonText(pipeline::fitsJson(*fits))));
  GLARECAM_CHECK(
      pipeline::publishDatasheet({.module = options.module,
                                  .date = day,
                                  .table = &sheet_table,
                                  .fits = &*fits,
                                  .model_beta_deg = std::nullopt,
                                  .limit = pipeline::inferGlareLimit(sheet_table)},
                                 (summary.directory / pipeline::kSweepTableFileName).string(),
                                 summary.directory, &sheet_contours));
  summary.datasheet = true;
  summary.detail = left_out.empty()
                       ? fmt::format("{} stacks, data sheet updated", summary.stacks)
                       : fmt::format("{} stacks, data sheet updated; {}", summary.stacks, left_out);
  return summary;
}

std::optional<DaySummary> readDayProducts(const DayProductsOptions& options,
                                          const std::string& day) {
  DaySummary summary{.day = day, .directory = options.root / kDaysDirectory / day};
  const auto table = pipeline::readSweepTable(summary.directory / pipeline::kSweepTableFileName);
  if (!table) return std::nullopt;
  summary.stacks = table->rows.size();
  std::error_code error;
  summary.datasheet = fs::is_regular_file(summary.directory / kFitsFileName, error) &&
                      fs::is_regular_file(summary.directory / kDatasheetPictureName, error);
  summary.detail = summary.datasheet
                       ? fmt::format("{} stacks, data sheet of an earlier run", summary.stacks)
                       : fmt::format("{} stacks; no data sheet yet", summary.stacks);
  return summary;
}

}  // namespace glarecam::daemon
