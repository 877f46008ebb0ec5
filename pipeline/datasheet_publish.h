// Publishing a sweep: the data sheet (datasheet.pdf/.svg/.png, datasheet.h) and the
// machine-readable glare profile (glare-profile.json, glare_profile.h) of one fitted sweep table,
// written together into one directory, each file atomically. `glarecam datasheet` publishes a
// sweep table through publishSweepTable(); glarecamd's per-day sheets through publishDatasheet().
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"
#include "pipeline/datasheet.h"
#include "pipeline/glare_fits.h"
#include "pipeline/glare_profile.h"

namespace glarecam::pipeline {

// `content` names the table and its fits; `source` is the sweep table's path (in the profile);
// `contours`, the sweep's contour table, gives the profile its ladder (none: an empty ladder).
Status publishDatasheet(const DatasheetContent& content, const std::string& source,
                        const std::filesystem::path& directory,
                        const ContourTable* contours = nullptr);

struct SweepPublishOptions {
  std::filesystem::path sweep;               // the sweep table (glarecam sweep's sweep.csv)
  std::optional<std::filesystem::path> out;  // default: the table's directory
  std::string module = "unnamed module";     // printed on the sheet; UTF-8
  std::string date;                          // printed on the sheet: sheetDate()
  // A constant limit instead of the one the sweep measured its ellipses at (sheetLimit()).
  std::optional<double> threshold_cd_m2;
  std::optional<double> model_beta_deg;  // the five-facet model's overlay, (0, 45]
  FitOptions fit;                        // include_suspect: fit the suspect rows too

  // The first problem in words (kBadInput), or nothing.
  Status validate() const;
};

// When `module` (--module, given: not the default) names none of the modules the table's stacks
// were recorded of (tableModules), the warning that says so; nullopt when it does, when the
// stacks name no module, or when --module was not given.
std::optional<std::string> moduleMismatch(const std::string& module, const SweepTable& table);

// Reads and fits the sweep table and publishes its sheet and profile; the PDF's path. The
// contour table beside the sweep table (contours.csv, as `glarecam sweep` writes it) gives the
// profile its ladder; without one the ladder is empty (a note in the log).
// Warns (moduleMismatch) when --module disagrees with the stacks' own module.
Result<std::filesystem::path> publishSweepTable(const SweepPublishOptions& options);

// The sheet's date: `date` (YYYY-MM-DD, checked), else SOURCE_DATE_EPOCH (reproducible builds),
// else today (UTC).
Result<std::string> sheetDate(const std::optional<std::string>& date);

// The limit a sheet shows: the one the sweep measured its ellipses at (the table's), which
// `threshold_cd_m2` may confirm. A different threshold is kBadInput naming `sweep`: the sheet's
// axes would be those at another limit than it shows (make the table with sweep --threshold).
Result<GlareLimit> sheetLimit(const std::string& sweep, const SweepTable& table,
                              const std::optional<double>& threshold_cd_m2);

}  // namespace glarecam::pipeline
