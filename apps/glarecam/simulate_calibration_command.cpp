// glarecam simulate-calibration: the simulated camera's calibration target stacks, each with its
// truth.json (capture/sim/calibration_targets.h, docs/calibration.md).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam::apps {
namespace {

struct SimulateTargetArgs {
  std::string target, out, seed = "1", sensor_seed = "1";
  std::optional<std::string> size;
  bool no_progress = false;
};

Status runSimulateTarget(const SimulateTargetArgs& args) {
  capture::CalibrationTargetOptions options;
  GLARECAM_ASSIGN(options.target, capture::parseCalibrationTarget(args.target));
  if (args.size) {
    std::pair<int, int> size;
    GLARECAM_ASSIGN(size, parseSize(*args.size, "--size"));
    std::tie(options.width, options.height) = size;
  }
  GLARECAM_ASSIGN(options.seed, parseUnsigned(args.seed, "--seed"));
  GLARECAM_ASSIGN(options.sensor_seed, parseUnsigned(args.sensor_seed, "--sensor-seed"));
  if (args.out.empty()) return badInput("--out: expected a directory");
  std::vector<capture::CalibrationTargetStack> stacks;
  GLARECAM_ASSIGN(stacks, capture::simulateCalibrationTarget(options));
  std::vector<std::filesystem::path> written;
  GLARECAM_ASSIGN(written, capture::writeCalibrationTargetStacks(args.out, options.target, stacks,
                                                                 !args.no_progress));
  for (const std::filesystem::path& path : written) std::printf("%s\n", path.c_str());
  return {};
}

}  // namespace

void addSimulateCalibrationCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<SimulateTargetArgs>();
  CLI::App* sub =
      app.add_subcommand("simulate-calibration",
                         "Write calibration target stacks of the simulated camera, with truth.json "
                         "(docs/calibration.md)");
  sub->add_option("TARGET", args->target, "dark, flat, linearity, noise, luminance or board")
      ->required();
  sub->add_option("--out", args->out, "directory the stacks go into")->required();
  sub->add_option(
      "--size", args->size,
      "WxH (default 320x256, for every target: a calibration's parts must share the size of the "
      "stacks it calibrates)");
  sub->add_option("--seed", args->seed, "noise seed (default 1)")->type_name("UINT");
  sub->add_option("--sensor-seed", args->sensor_seed,
                  "places the sensor's defects (dark: 12 hot pixels, a 0.5 DN fixed pattern); "
                  "`simulate --sensor-seed` with the same seed and size has the same (default 1)")
      ->type_name("UINT");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runSimulateTarget(*args); }; });
}

}  // namespace glarecam::apps
