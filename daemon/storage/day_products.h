// The daemon's output tree and each day's products. Under the output root:
//
//   stacks/<id>/     every stack, written atomically (docs/stack-format.md)
//   results/<id>/    its result: result.json, luminance.png, luminance.exr, quality.exr
//   days/<day>/      the day's sweep.csv, fits.json, datasheet.pdf/.svg/.png, glare-profile.json
//
// A day is the site's mean solar day (UTC shifted by longitude / 15° per hour), so that a sweep
// over α, morning and afternoon, lands on one sheet wherever the rig stands; UTC without a site.
// A stack belongs to the day of the time in its id ("20260621T101503Z-a42.30"). The day's table
// is rebuilt from the results on disk each time, so a restart, a crash or a stack processed late
// never loses or doubles a row; the rows of stacks whose result is gone (retention's tier 3,
// retention.h, or removed by hand) are kept from the table as it was.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/time.h"
#include "pipeline/datasheet.h"  // kDatasheetPng

namespace glarecam::daemon {

inline constexpr const char* kStacksDirectory = "stacks";
inline constexpr const char* kResultsDirectory = "results";
inline constexpr const char* kDaysDirectory = "days";
inline constexpr const char* kFitsFileName = "fits.json";
inline constexpr const char* kDatasheetPictureName = pipeline::kDatasheetPng;

// "2026-06-21", or nullopt when the id does not start with a UTC time stamp YYYYMMDDTHHMMSSZ.
std::optional<std::string> stackDay(std::string_view stack_id, std::optional<double> longitude_deg);
// The day of an instant, as stackDay names the day of a stack taken then.
std::string solarDay(UtcTime utc, std::optional<double> longitude_deg);

struct DayProductsOptions {
  std::filesystem::path root;
  std::string module = "unnamed module";
  std::optional<double> longitude_deg;  // the site's; none: UTC days
};

struct DaySummary {
  std::string day;
  std::filesystem::path directory;
  std::size_t stacks = 0;  // rows of the day's sweep table
  bool datasheet = false;  // the fits succeeded and the sheet was (re)written
  std::string detail{};    // "16 stacks, data sheet updated", or why not
};

// Rebuilds days/<day>/ from the results of that day's stacks. Fails (kIo) only when a file
// cannot be written; too few stacks for the fits is a summary without a data sheet.
Result<DaySummary> updateDayProducts(const DayProductsOptions& options, const std::string& day);

// What days/<day>/ holds as updateDayProducts last left it, without rebuilding anything: for a
// glarecamd that starts again during a day. Nullopt when the day has no readable sweep table.
std::optional<DaySummary> readDayProducts(const DayProductsOptions& options,
                                          const std::string& day);

}  // namespace glarecam::daemon
