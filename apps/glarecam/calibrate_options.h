// What the `glarecam calibrate` subcommands share (one file each: calibrate_*_command.cpp): the
// options of a part (its stacks, or --camera to capture them; the earlier parts; --out, --json,
// --no-progress), capturing its stacks (capture/calibration_series.h), running it
// (calibration/calibration_parts.h) and printing what it wrote.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apps/glarecam/commands.h"
#include "calibration/calibration_parts.h"
#include "calibration/frame_statistics.h"
#include "core/error.h"

namespace glarecam::apps {

// The subcommands of `calibrate`, in the order its help lists them.
void addCalibrateDarkCommand(CLI::App& calibrate, Action& action);
void addCalibrateFlatCommand(CLI::App& calibrate, Action& action);
void addCalibrateLinearityCommand(CLI::App& calibrate, Action& action);
void addCalibrateNoiseCommand(CLI::App& calibrate, Action& action);
void addCalibrateLuminanceCommand(CLI::App& calibrate, Action& action);
void addCalibrateIntrinsicsCommand(CLI::App& calibrate, Action& action);
void addCalibrateMergeCommand(CLI::App& calibrate, Action& action);

struct PartArgs {
  std::vector<std::string> stacks;               // STACK...
  std::optional<std::string> camera, exposures;  // capture instead of reading stacks
  double gain_db = 0;
  int views = 1;                          // intrinsics: board poses to capture
  double view_interval_s = 10;            // ... this long apart (the operator moves the board)
  std::vector<std::string> calibrations;  // --calibration, merged in order
  std::optional<std::string> out;
  bool json = false, no_progress = false;
};

// A part's subcommand with the options every part has (--calibration when it reads earlier parts).
CLI::App* addPartCommand(CLI::App& calibrate, const std::string& name, const std::string& help,
                         PartArgs& args, bool reads_prior);
void addRoiOption(CLI::App* sub, std::optional<std::string>& roi);
Result<std::optional<calibration::Roi>> parseRoiOption(const std::optional<std::string>& roi);

// When the subcommand is chosen, `action` runs `run` on its parsed arguments.
template <typename Args>
void setAction(CLI::App* sub, Action& action, std::shared_ptr<Args> args,
               Status (*run)(const Args&)) {
  sub->callback([args, run, &action] { action = [args, run] { return run(*args); }; });
}

// The part's stacks, out file and earlier parts as given (no stacks yet with --camera).
Result<calibration::PartInputs> partInputs(const PartArgs& args);
// With --camera: captures the stacks beside the part's file (<out>-stacks/) into `inputs`.
Status captureStacks(const PartArgs& args, calibration::PartInputs& inputs);
// The part's file with --json, else its method, its values and the file's path.
void printPart(const calibration::PartReport& report, bool as_json);

// A part's run: its options validated before anything is captured, its stacks (given or
// captured), `calibrate` run and its part printed.
template <typename Options, typename Part>
Status runPart(const PartArgs& args, Options options, Result<Part> (*calibrate)(const Options&)) {
  GLARECAM_ASSIGN(options.inputs, partInputs(args));
  GLARECAM_CHECK(options.validate());
  GLARECAM_CHECK(captureStacks(args, options.inputs));
  Part part;
  GLARECAM_ASSIGN(part, calibrate(options));
  printPart(part.report, args.json);
  return {};
}

}  // namespace glarecam::apps
