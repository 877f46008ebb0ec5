#include "pipeline/datasheet_publish.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "core/atomic_file.h"
#include "core/json.h"
#include "core/time.h"
#include "core/utf8.h"
#include "pipeline/facet_model.h"
#include "pipeline/glare_fits.h"

namespace glarecam::pipeline {

namespace fs = std::filesystem;

Status publishDatasheet(const DatasheetContent& content, const std::string& source,
                        const std::filesystem::path& directory, const ContourTable* contours) {
  GLARECAM_CHECK(writeDatasheet(content, directory));
  const GlareProfile profile =
      makeGlareProfile({.module = content.module, .date = content.date, .source = source},
                       *content.table, *content.fits, content.limit, contours);
  return writeJsonFile(directory / kGlareProfileFileName, toJson(profile));
}

Status SweepPublishOptions::validate() const {
  if (out && out->empty()) return badInput("--out: expected a path, got an empty string");
  GLARECAM_CHECK(requireUtf8(module, "--module"));
  if (model_beta_deg && !(*model_beta_deg > 0 && *model_beta_deg <= kMaxFacetTiltDeg))
    return badInput("--model-beta: expected a facet tilt in (0, 45] degrees");
  return {};
}

std::optional<std::string> moduleMismatch(const std::string& module, const SweepTable& table) {
  if (module == SweepPublishOptions{}.module) return std::nullopt;  // not given
  const std::vector<std::string> modules = tableModules(table);
  if (modules.empty() || std::ranges::find(modules, module) != modules.end()) return std::nullopt;
  return fmt::format(
      "--module \"{}\" is not the module the stacks were recorded of (\"{}\"); "
      "the sheet says \"{}\"",
      module, fmt::join(modules, "\", \""), module);
}

Result<fs::path> publishSweepTable(const SweepPublishOptions& options) {
  GLARECAM_CHECK(options.validate());
  SweepTable table;
  SweepFits fits;
  GLARECAM_ASSIGN(fits, readAndFitSweep(options.sweep, table, options.fit));
  if (const auto mismatch = moduleMismatch(options.module, table))
    spdlog::warn("{}: {}", options.sweep.string(), *mismatch);
  GlareLimit limit;
  GLARECAM_ASSIGN(limit, sheetLimit(options.sweep.string(), table, options.threshold_cd_m2));
  const fs::path out = options.out.value_or(options.sweep.parent_path());
  if (!out.empty()) GLARECAM_CHECK(ensureDirectory(out));
  std::optional<ContourTable> contours;
  const fs::path contours_csv = options.sweep.parent_path() / kContourTableFileName;
  std::error_code ec;
  if (fs::exists(contours_csv, ec)) {
    GLARECAM_ASSIGN(contours, readContourTable(contours_csv));
  } else {
    spdlog::info("{}: no {} beside it: the glare profile's ladder is empty", options.sweep.string(),
                 kContourTableFileName);
  }
  GLARECAM_CHECK(publishDatasheet({.module = options.module,
                                   .date = options.date,
                                   .table = &table,
                                   .fits = &fits,
                                   .model_beta_deg = options.model_beta_deg,
                                   .limit = limit},
                                  options.sweep.string(), out, contours ? &*contours : nullptr));
  return out / kDatasheetPdf;
}

Result<std::string> sheetDate(const std::optional<std::string>& date) {
  if (date) {
    const auto day = parseIsoDay(*date);
    if (!day) return badInput("--date " + day.error().message);
    return *date;
  }
  std::time_t seconds = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    unsigned long long value = 0;
    const char* end = epoch + std::char_traits<char>::length(epoch);
    const auto [stop, error] = std::from_chars(epoch, end, value);
    if (error != std::errc() || stop != end || epoch == end)
      return badInput(
          fmt::format("SOURCE_DATE_EPOCH: expected a whole number >= 0, got \"{}\"", epoch));
    seconds = static_cast<std::time_t>(value);
  }
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:%F}", utc);
}

Result<GlareLimit> sheetLimit(const std::string& sweep, const SweepTable& table,
                              const std::optional<double>& threshold_cd_m2) {
  std::string warning;
  const GlareLimit measured = inferGlareLimit(table, &warning);
  if (!warning.empty()) spdlog::warn("{}: {}", sweep, warning);
  if (!threshold_cd_m2) return measured;
  if (measured.constant_cd_m2 != threshold_cd_m2)
    return badInput(fmt::format(
        "{}: --threshold {:g} cd/m² differs from the limit the sweep measured its ellipses at "
        "({}): a sheet must show the limit its axes were measured at; make the table with "
        "glarecam sweep --threshold {:g}",
        sweep, *threshold_cd_m2,
        measured.constant_cd_m2 ? fmt::format("{:g} cd/m²", *measured.constant_cd_m2)
                                : std::string("the α curve"),
        *threshold_cd_m2));
  return GlareLimit{.constant_cd_m2 = threshold_cd_m2};
}

}  // namespace glarecam::pipeline
