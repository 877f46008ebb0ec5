// glarecam simulate: writes a stack of the simulated rig (capture/sim/simulated_stack.h).
#include <cstdio>
#include <memory>
#include <optional>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "capture/sim/module_model.h"
#include "capture/sim/simulated_stack.h"
#include "core/stack_io.h"

namespace glarecam::apps {
namespace {

struct SimulateArgs {
  bool no_progress = false;
  std::string out;
  std::string size = "1224x1024";
  std::optional<std::string> distortion, offset;  // given but empty is an error
  std::optional<std::string> source_illuminance;
  bool unreferred = false;
  std::string seed = "1";
  std::string sensor_seed = "1";
  std::optional<std::string> module;  // --module NAME: --surface curves:NAME
  capture::SimulationOptions options;
};

Status runSimulate(SimulateArgs& args) {
  if (args.module) args.options.surface = std::string(capture::kCurvesPrefix) + *args.module;
  auto size = parseSize(args.size, "--size");
  if (!size) return std::unexpected(size.error());
  std::tie(args.options.width, args.options.height) = *size;
  auto seed = parseUnsigned(args.seed, "--seed");
  if (!seed) return std::unexpected(seed.error());
  args.options.seed = *seed;
  auto sensor_seed = parseUnsigned(args.sensor_seed, "--sensor-seed");
  if (!sensor_seed) return std::unexpected(sensor_seed.error());
  args.options.sensor_seed = *sensor_seed;
  if (args.distortion) {
    auto k = parseNumberList(*args.distortion, "--distortion", 1, 5);
    if (!k) return std::unexpected(k.error());
    std::copy(k->begin(), k->end(), args.options.distortion.begin());
  }
  if (args.offset) {
    auto offset = parseNumberList(*args.offset, "--offset-deg", 2, 2);
    if (!offset) return std::unexpected(offset.error());
    args.options.lobe_offset_deg = {(*offset)[0], (*offset)[1]};
  }
  if (args.source_illuminance) {
    if (args.unreferred)
      return badInput("--unreferred: a stack cannot record --source-illuminance and none");
    SourceIlluminance source;
    GLARECAM_ASSIGN(source,
                    parseGivenIlluminance(*args.source_illuminance, "--source-illuminance"));
    args.options.source_illuminance_lx = source.illuminance_lx;
    args.options.source_illuminance_u_lx = source.illuminance_u_lx;
  }
  args.options.record_source = !args.unreferred;
  args.options.show_progress = !args.no_progress;
  // Refuse a bad --out before spending seconds on the simulation.
  if (auto target = stackTarget(args.out); !target) return std::unexpected(target.error());
  auto stack = capture::simulateStack(args.options);
  if (!stack) return std::unexpected(stack.error());
  GLARECAM_CHECK(capture::writeSimulatedStack(args.out, *stack));
  std::printf("%s\n", args.out.c_str());
  return {};
}

}  // namespace

void addSimulateCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<SimulateArgs>();
  std::string modules;
  for (const auto& name : capture::moduleNames()) modules += (modules.empty() ? "" : ", ") + name;
  CLI::App* sub = app.add_subcommand(
      "simulate", "Write a stack of the simulated rig, with truth.json (docs/simulate.md)");
  sub->add_option("--out", args->out,
                  "stack directory to create; an existing stack there is replaced atomically, "
                  "anything else is refused")
      ->required();
  sub->add_option("--alpha", args->options.alpha_deg, "angle of incidence in degrees, 0..80")
      ->capture_default_str();
  auto* module = sub->add_option("--module", args->module,
                                 "the lobe of a module's empirical curves (" + modules +
                                     "): the same as --surface curves:MODULE");
  sub->add_option(
         "--surface", args->options.surface,
         "what the camera looks at: a physical surface (standard, glare-reduced, gaussian or a "
         "surface FILE.toml, rendered under the sun's disc, truth from its own contours) "
         "or curves:MODULE, the lobe of a module's empirical curves (docs/brdf.md)")
      ->capture_default_str()
      ->excludes(module);
  sub->add_option("--size", args->size, "frame size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--seed", args->seed, "noise seed (whole number >= 0); same seed, same stack")
      ->capture_default_str()
      ->type_name("UINT");
  sub->add_option("--fov", args->options.horizontal_fov_deg, "horizontal field of view in degrees")
      ->capture_default_str();
  sub->add_option("--distortion", args->distortion,
                  "lens distortion k1,k2,p1,p2,k3 (OpenCV order)");
  sub->add_option("--offset-deg", args->offset, "lobe centre H,V degrees from the optical axis");
  sub->add_option("--orientation", args->options.lobe_orientation_deg, "lobe rotation in degrees")
      ->capture_default_str();
  sub->add_option("--background", args->options.background_cd_m2, "background luminance, cd/m²")
      ->capture_default_str();
  sub->add_option("--source-illuminance", args->source_illuminance,
                  "the simulated sun's direct normal illuminance in lx (default 100000, the "
                  "reference): it scales the whole scene and is recorded as the stack's source, "
                  "with the uncertainty given (92500±2800)")
      ->option_text("LX[±U]");
  sub->add_flag("--unreferred", args->unreferred,
                "record no source illuminance: a stack as an older rig or another tool writes "
                "it, processed unreferred");
  sub->add_option("--peak-scale", args->options.peak_scale, "scale the module's luminance maximum")
      ->capture_default_str();
  sub->add_option("--hot-pixels", args->options.defects.hot_pixels,
                  "hot pixels of the sensor (dark current 20-60 DN/ms), up to 1 % of the pixels")
      ->capture_default_str();
  sub->add_option("--fixed-pattern", args->options.defects.fixed_pattern_dn,
                  "standard deviation of the sensor's per-pixel offset, DN (0..100)")
      ->capture_default_str();
  sub->add_option("--sensor-seed", args->sensor_seed,
                  "places the sensor's defects; simulate-calibration dark with the same seed "
                  "and size measures the same ones")
      ->capture_default_str()
      ->type_name("UINT");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runSimulate(*args); }; });
}

}  // namespace glarecam::apps
