// glarecam datasheet: a sweep table -> datasheet.pdf/.svg/.png and glare-profile.json
// (docs/datasheet.md, docs/glare-profile.md).
#include <fmt/chrono.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "core/atomic_file.h"
#include "core/stack_manifest.h"
#include "pipeline/datasheet_publish.h"
#include "pipeline/facet_model.h"

namespace glarecam::apps {
namespace {

namespace fs = std::filesystem;

struct DatasheetArgs {
  std::string sweep;
  std::optional<std::string> out, date, threshold;
  std::string module = "unnamed module";
  std::optional<double> model_beta_deg;
};

// The sheet's date: --date, else SOURCE_DATE_EPOCH (reproducible builds), else today (UTC).
Result<std::string> sheetDate(const std::optional<std::string>& date) {
  if (date) {
    int year = 0;
    unsigned month = 0, day = 0;
    char tail = 0;
    const bool parsed =
        std::sscanf(date->c_str(), "%4d-%2u-%2u%c", &year, &month, &day, &tail) == 3;
    if (!parsed || date->size() != 10 ||
        !std::chrono::year_month_day(std::chrono::year(year), std::chrono::month(month),
                                     std::chrono::day(day))
             .ok())
      return badInput("--date: expected a date YYYY-MM-DD, got \"" + *date + "\"");
    return *date;
  }
  std::time_t seconds = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    auto parsed = parseUnsigned(epoch, "SOURCE_DATE_EPOCH");
    if (!parsed) return std::unexpected(parsed.error());
    seconds = static_cast<std::time_t>(*parsed);
  }
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:%F}", utc);
}

// --threshold, else the limit the sweep used (from the table). The ellipses were measured at the
// sweep's limit: a different --threshold changes the verdict, not the axes, so say so.
pipeline::GlareLimit sheetLimit(const std::string& sweep, const pipeline::SweepTable& table,
                                const std::optional<double>& threshold_cd_m2) {
  std::string warning;
  const pipeline::GlareLimit measured = pipeline::inferGlareLimit(table, &warning);
  if (!warning.empty()) spdlog::warn("{}: {}", sweep, warning);
  if (!threshold_cd_m2) return measured;
  if (measured.constant_cd_m2 != threshold_cd_m2)
    spdlog::warn(
        "{}: --threshold {:g} cd/m² differs from the limit the sweep measured its "
        "ellipses at ({}); the sheet's glare verdict follows --threshold, the axes do not",
        sweep, *threshold_cd_m2,
        measured.constant_cd_m2 ? fmt::format("{:g} cd/m²", *measured.constant_cd_m2)
                                : std::string("the α curve"));
  return {.constant_cd_m2 = threshold_cd_m2};
}

Status runDatasheet(const DatasheetArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  GLARECAM_CHECK(requireUtf8(args.module, "--module"));
  if (args.model_beta_deg &&
      !(*args.model_beta_deg > 0 && *args.model_beta_deg <= pipeline::kMaxFacetTiltDeg))
    return badInput("--model-beta: expected a facet tilt in (0, 45] degrees");
  std::string date;
  GLARECAM_ASSIGN(date, sheetDate(args.date));
  std::optional<double> threshold_cd_m2;
  GLARECAM_ASSIGN(threshold_cd_m2, parseOptionalLuminance(args.threshold, "--threshold"));
  pipeline::SweepTable table;
  pipeline::SweepFits fits;
  GLARECAM_ASSIGN(fits, readAndFitSweep(args.sweep, table));
  const pipeline::GlareLimit limit = sheetLimit(args.sweep, table, threshold_cd_m2);
  const fs::path out = args.out ? fs::path(*args.out) : fs::path(args.sweep).parent_path();
  if (!out.empty()) GLARECAM_CHECK(ensureDirectory(out));
  GLARECAM_CHECK(pipeline::publishDatasheet({.module = args.module,
                                             .date = date,
                                             .table = &table,
                                             .fits = &fits,
                                             .model_beta_deg = args.model_beta_deg,
                                             .limit = limit},
                                            args.sweep, out));
  std::printf("%s\n", (out / pipeline::kDatasheetPdf).c_str());
  return {};
}

}  // namespace

void addDatasheetCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<DatasheetArgs>();
  CLI::App* sub = app.add_subcommand(
      "datasheet",
      "Write the module glare data sheet (PDF, SVG, PNG) and glare-profile.json from a sweep "
      "table (docs/datasheet.md)");
  sub->add_option("SWEEP", args->sweep, "sweep table CSV (glarecam sweep's sweep.csv)")->required();
  sub->add_option("--out", args->out, "output directory (default: the sweep table's directory)");
  sub->add_option("--module", args->module, "module name printed on the sheet")
      ->capture_default_str();
  sub->add_option("--date", args->date,
                  "date printed on the sheet, YYYY-MM-DD (default: SOURCE_DATE_EPOCH or today)");
  sub->add_option("--threshold", args->threshold,
                  "constant glare limit in cd/m² (default: the one the sweep used, read from the "
                  "table's limit_cd_m2: the α curve or a constant)");
  sub->add_option("--model-beta", args->model_beta_deg,
                  "overlay the five-facet model with facet tilt β in degrees (glarecam model)");
  sub->callback([args, &action] { action = [args] { return runDatasheet(*args); }; });
}

}  // namespace glarecam::apps
