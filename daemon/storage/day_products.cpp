#include "daemon/storage/day_products.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>

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

// Whether a sweep table's text has a row (a line that is neither the header, a '#' note nor
// blank): one that holds rows but cannot be read must not be overwritten unseen.
bool tableTextHasRows(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line.starts_with('#')) continue;
    if (header) {
      header = false;
      continue;
    }
    return true;
  }
  return false;
}

// The rows (and ladders) the day's tables hold for stacks whose result is gone (retention's tier
// 3, retention.h, or removed by hand): their numbers live on only there, so a rebuild keeps them.
// A row already rebuilt from its result (a result that went while this rebuild read it) is not
// kept twice. An earlier table with rows that cannot be read is kept aside as sweep.csv.unreadable
// (and logged), never lost.
void keepRowsOfDeletedResults(const DayProductsOptions& options, const std::string& day,
                              pipeline::SweepTable& table, pipeline::ContourTable& contours) {
  const fs::path directory = options.root / kDaysDirectory / day;
  const fs::path results = options.root / kResultsDirectory;
  std::set<std::string> rebuilt;
  for (const pipeline::SweepRow& row : table.rows) rebuilt.insert(row.stack_id);
  const auto gone = [&](const std::string& id) {
    std::error_code error;
    return !id.empty() && !rebuilt.contains(id) && fs::path(id).filename() == fs::path(id) &&
           !fs::exists(fs::symlink_status(results / id, error));
  };
  std::error_code error;
  const fs::path table_path = directory / pipeline::kSweepTableFileName;
  if (!fs::is_regular_file(table_path, error)) return;
  const auto old_table = pipeline::readSweepTable(table_path);
  if (!old_table) {
    if (!tableTextHasRows(table_path)) return;  // notes only: nothing to keep
    const fs::path aside = directory / (std::string(pipeline::kSweepTableFileName) + ".unreadable");
    const fs::path staging = directory / (std::string(kTemporaryPrefix) + "sweep.csv.unreadable");
    fs::copy_file(table_path, staging, fs::copy_options::overwrite_existing, error);
    if (!error) fs::rename(staging, aside, error);
    spdlog::warn("day {}: the earlier table cannot be read ({}); kept as {}{}", day,
                 old_table.error().message, aside.string(),
                 error ? " failed: " + error.message() : "");
    return;
  }
  std::set<std::string> kept;
  for (const pipeline::SweepRow& row : old_table->rows)
    if (gone(row.stack_id) && kept.insert(row.stack_id).second) table.rows.push_back(row);
  if (kept.empty()) return;
  const auto old_contours = pipeline::readContourTable(directory / pipeline::kContourTableFileName);
  if (!old_contours) return;  // the rows stay; their ladders are lost with the earlier file
  for (const pipeline::ContourRow& contour : old_contours->rows)
    if (kept.contains(contour.stack_id)) contours.rows.push_back(contour);
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
