// glarecam process: one stack -> luminance.exr, luminance.png, result.json (docs/process.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>

#include "apps/glarecam/commands.h"
#include "pipeline/process_stack.h"

namespace glarecam::apps {
namespace {

struct ProcessArgs {
  std::string stack;
  std::string calibration, out;
  bool json = false, no_progress = false;
  unsigned threads = 0;
};

Status runProcess(const ProcessArgs& args) {
  pipeline::ProcessOptions options;
  if (!args.calibration.empty()) options.calibration_file = args.calibration;
  if (!args.out.empty()) options.output_directory = args.out;
  options.threads = args.threads;
  options.show_progress = !args.no_progress;
  auto summary = pipeline::processStack(args.stack, options);
  if (!summary) return std::unexpected(summary.error());
  spdlog::info("{}", summary->briefReport());
  if (args.json) {
    std::printf("%s\n", summary->result.dump(2).c_str());
  } else {
    std::printf("%s\n", summary->output_directory.c_str());
  }
  return {};
}

}  // namespace

void addProcessCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<ProcessArgs>();
  CLI::App* sub = app.add_subcommand(
      "process", "Turn a stack into a luminance image and result.json (docs/process.md)");
  sub->add_option("STACK", args->stack, "stack directory (holding stack.json)")->required();
  sub->add_option("--calibration", args->calibration,
                  "calibration JSON file; overrides the stack's");
  sub->add_option("--out", args->out, "output directory (default STACK/result)");
  sub->add_flag("--json", args->json, "print result.json on stdout");
  sub->add_option("--threads", args->threads, "worker threads (default: all cores)");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runProcess(*args); }; });
}

}  // namespace glarecam::apps
