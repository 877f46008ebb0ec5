// The module glare data sheet (docs/datasheet.md) drawn with Cairo: Lmax against α on a log
// axis with the limit curve and both fitted luminance functions, the two limit-ellipse axes
// against α with their logistic fits (and optionally the five-facet model), the sweep table and
// the fit parameters with R², module name and date. One drawing, three outputs: datasheet.pdf
// and datasheet.svg (vector, A4 landscape) and datasheet.png (a raster preview).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"
#include "pipeline/glare_fits.h"
#include "pipeline/limit_curve.h"
#include "pipeline/sweep_table.h"
#include "render/text_table.h"

namespace glarecam::pipeline {

struct DatasheetContent {
  std::string module;
  std::string date;  // ISO 8601 day
  const SweepTable* table = nullptr;
  const SweepFits* fits = nullptr;
  std::optional<double> model_beta_deg;  // overlay the five-facet model's 2γ curves
  GlareLimit limit;                      // the limit curve drawn (the α curve or a constant)
};

inline constexpr const char* kDatasheetPdf = "datasheet.pdf";
inline constexpr const char* kDatasheetSvg = "datasheet.svg";
inline constexpr const char* kDatasheetPng = "datasheet.png";

// The sheet's table of the sweep's rows, cell by cell as drawn (α rounded to its uncertainty, Lmax
// to 4 significant digits, axes to 2 decimals).
render::TextTable datasheetSweepTable(const SweepTable& sweep);

// The word drawn across the sheet's face and its note: "SIMULATED" for the simulated camera's
// stacks, "UNREFERRED" for luminances at the day's own sun (docs/datasheet.md), none otherwise.
struct PageMark {
  std::string word, note;
};
std::optional<PageMark> datasheetPageMark(const SweepTable& sweep);

// Writes the three files into directory (which must exist), each atomically.
Status writeDatasheet(const DatasheetContent& content, const std::filesystem::path& directory);

}  // namespace glarecam::pipeline
