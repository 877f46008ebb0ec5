// glarecam sweep: stacks over α -> sweep.csv and each stack's result (docs/sweep.md).
#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "pipeline/process_stack.h"
#include "pipeline/sweep.h"

namespace glarecam::apps {
namespace {

struct SweepArgs {
  std::vector<std::string> inputs;
  std::optional<std::string> out, calibration, threshold, alpha_from;
  unsigned jobs = 0, threads = 0, memory_mib = 0;
  bool no_progress = false, strict = false, mixed = false, float32 = false;
};

Status runSweep(const SweepArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  GLARECAM_CHECK(requireNonEmptyPath(args.calibration, "--calibration"));
  pipeline::SweepOptions options;
  if (args.out) options.output_directory = *args.out;
  if (args.calibration) options.calibration_file = *args.calibration;
  GLARECAM_ASSIGN(options.threshold_cd_m2, parseOptionalLuminance(args.threshold, "--threshold"));
  options.jobs = args.jobs;
  options.threads = args.threads;
  options.memory_budget_bytes = std::uint64_t{args.memory_mib} << 20;
  options.show_progress = !args.no_progress;
  options.allow_mixed = args.mixed;
  options.float32 = args.float32;
  GLARECAM_CHECK(requireNonEmptyPath(args.alpha_from, "--alpha-from"));
  if (args.alpha_from)
    GLARECAM_ASSIGN(options.given_alpha_deg, pipeline::readAlphaTable(*args.alpha_from));
  std::vector<std::filesystem::path> inputs;
  for (const std::string& input : args.inputs) {
    if (input.empty()) return badInput("STACKS: expected a path, got an empty string");
    inputs.emplace_back(input);
  }
  pipeline::SweepSummary summary;
  GLARECAM_ASSIGN(summary, pipeline::runSweep(pipeline::findStacks(inputs), options));
  spdlog::info("sweep: {} stacks processed, {} skipped; results under {}",
               summary.table.rows.size(), summary.skipped.size(),
               (options.output_directory / pipeline::kSweepResultsDirectory).string());
  std::printf("%s\n", summary.sweep_csv.c_str());
  if (args.strict) return pipeline::checkStrict(summary);
  return {};
}

}  // namespace

void addSweepCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* sub = app.add_subcommand(
      "sweep", "Process stacks over α in parallel into sweep.csv (docs/sweep.md)");
  sub->add_option("STACKS", args->inputs,
                  "stack directories, or directories holding stacks (one level down)")
      ->required();
  sub->add_option("--out", args->out,
                  "output directory for sweep.csv and results/<stack>/ (default ./sweep)");
  sub->add_option("--jobs", args->jobs,
                  "stacks processed at once (default: one per thread of --threads)")
      ->check(CLI::Range(1u, 1024u));
  sub->add_option("--threads", args->threads,
                  "threads in all, shared by the jobs, every step keeping to its share "
                  "(default: all cores)")
      ->check(CLI::Range(1u, 1024u));
  sub->add_option("--memory", args->memory_mib,
                  "MiB the jobs may hold at once: fewer jobs run when they would not fit (default: "
                  "half the physical memory)")
      ->check(CLI::Range(1u, 1u << 24));
  sub->add_option("--calibration", args->calibration,
                  "calibration JSON file for every stack; overrides the stacks' own");
  sub->add_option("--threshold", args->threshold,
                  "constant glare limit in cd/m² instead of the α curve (e.g. 30000)");
  sub->add_flag("--strict", args->strict,
                "exit non-zero when any stack or input was skipped, or any row is suspect (frames "
                "that disagree); the table is still written");
  sub->add_option("--alpha-from", args->alpha_from,
                  "CSV with columns stack (a stack directory's name) and alpha_deg: α for stacks "
                  "that record none (result.json: alpha_source given)");
  sub->add_flag("--mixed", args->mixed,
                "write one table of stacks of different cameras, frame sizes or calibrations "
                "(refused otherwise; a '# mixed' note says what differs)");
  sub->add_flag("--float32", args->float32,
                "each result's images in lossless float32 (as process --float32)");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runSweep(*args); }; });
}

}  // namespace glarecam::apps
