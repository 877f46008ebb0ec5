// glarecam datasheet: a sweep table -> datasheet.pdf/.svg/.png and glare-profile.json
// (docs/datasheet.md, docs/glare-profile.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "pipeline/datasheet_publish.h"

namespace glarecam::apps {
namespace {

struct DatasheetArgs {
  std::string sweep;
  std::optional<std::string> out, date, threshold;
  std::string module = "unnamed module";
  std::optional<double> model_beta_deg;
  bool include_suspect = false;
  bool mixed = false;
};

Status runDatasheet(const DatasheetArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  pipeline::SweepPublishOptions publish{
      .sweep = args.sweep,
      .out = std::nullopt,
      .module = args.module,
      .date = {},
      .threshold_cd_m2 = std::nullopt,
      .model_beta_deg = args.model_beta_deg,
      .fit = {.include_suspect = args.include_suspect, .allow_mixed_references = args.mixed}};
  if (args.out) publish.out = *args.out;
  GLARECAM_CHECK(publish.validate());
  GLARECAM_ASSIGN(publish.date, pipeline::sheetDate(args.date));
  GLARECAM_ASSIGN(publish.threshold_cd_m2, parseOptionalLuminance(args.threshold, "--threshold"));
  std::filesystem::path pdf;
  GLARECAM_ASSIGN(pdf, pipeline::publishSweepTable(publish));
  std::printf("%s\n", pdf.c_str());
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
                  "the sweep's constant glare limit in cd/m², to confirm it (default: the one the "
                  "sweep used, read from the table's limit_cd_m2; another is refused: the axes "
                  "were measured at the sweep's)");
  sub->add_option("--model-beta", args->model_beta_deg,
                  "overlay the five-facet model with facet tilt β in degrees (glarecam model)");
  sub->add_flag("--mixed", args->mixed, kMixedReferencesHelp);
  sub->add_flag("--include-suspect", args->include_suspect,
                "fit the suspect rows too (frames that disagree with the merge; default: drawn "
                "hollow, listed and left out)");
  sub->callback([args, &action] { action = [args] { return runDatasheet(*args); }; });
}

}  // namespace glarecam::apps
