// glarecam fit: the empirical functions of docs/method.md fitted to a sweep table
// (docs/sweep.md).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "core/json.h"
#include "pipeline/glare_fits.h"

namespace glarecam::apps {

namespace {

struct FitArgs {
  std::string sweep;
  bool json = false;
  bool include_suspect = false;
  bool mixed = false;
};

Status runFit(const FitArgs& args) {
  pipeline::SweepTable table;
  pipeline::SweepFits fits;
  GLARECAM_ASSIGN(fits, pipeline::readAndFitSweep(args.sweep, table,
                                                  {.include_suspect = args.include_suspect,
                                                   .allow_mixed_references = args.mixed}));
  if (args.json) {
    std::printf("%s", jsonText(pipeline::fitsJson(fits)).c_str());
  } else {
    std::printf("%s", pipeline::fitsReport(fits).c_str());
  }
  return {};
}

}  // namespace

void addFitCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<FitArgs>();
  CLI::App* sub =
      app.add_subcommand("fit", "Fit the method's functions of α to a sweep table (docs/sweep.md)");
  sub->add_option("SWEEP", args->sweep, "sweep table CSV (glarecam sweep's sweep.csv)")->required();
  sub->add_flag("--json", args->json, "print the fits as JSON (keys in docs/sweep.md)");
  sub->add_flag("--mixed", args->mixed, kMixedReferencesHelp);
  sub->add_flag("--include-suspect", args->include_suspect,
                "fit the suspect rows too (frames that disagree with the merge; default: left "
                "out with a warning)");
  sub->callback([args, &action] { action = [args] { return runFit(*args); }; });
}

}  // namespace glarecam::apps
