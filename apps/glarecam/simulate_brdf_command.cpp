// glarecam simulate-brdf: a surface measured by the simulated goniophotometer, in the lab's file
// formats (docs/brdf.md, "Simulated measurements").
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "brdf/simulated_goniophotometer.h"
#include "surface/surface_catalogue.h"

namespace glarecam::apps {
namespace {

struct SimulateBrdfArgs {
  std::string surface = "standard";
  std::string out;
  std::string format = "both";
  std::optional<std::string> alpha;
  double noise = 0.01, fine_step_deg = 0.1;
  std::uint64_t seed = 1;
};

Status runSimulateBrdf(const SimulateBrdfArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  std::unique_ptr<surface::BrdfModel> model;
  GLARECAM_ASSIGN(model, surface::surfaceModel(args.surface));
  brdf::GoniophotometerOptions options;
  if (args.alpha)
    GLARECAM_ASSIGN(options.alphas_deg, parseNumberList(*args.alpha, "--alpha", 1, 90));
  options.relative_noise = args.noise;
  options.fine_step_deg = args.fine_step_deg;
  options.seed = args.seed;
  options.sample_name = args.surface;
  const brdf::SimulatedFormats formats = args.format == "pabopto" ? brdf::SimulatedFormats::kPabOpto
                                         : args.format == "zemax" ? brdf::SimulatedFormats::kZemax
                                                                  : brdf::SimulatedFormats::kBoth;
  spdlog::info("simulate-brdf: {}", model->describe());
  brdf::SimulatedFiles files;
  GLARECAM_ASSIGN(files, brdf::writeSimulatedMeasurements(*model, options, formats, args.out));
  for (const auto& file : files.pabopto) std::printf("%s\n", file.c_str());
  if (!files.zemax.empty()) std::printf("%s\n", files.zemax.c_str());
  std::printf("%s\n", files.truth.c_str());
  return {};
}

}  // namespace

void addSimulateBrdfCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<SimulateBrdfArgs>();
  CLI::App* sub = app.add_subcommand(
      "simulate-brdf",
      "A surface measured by the simulated goniophotometer: pab-opto files (one per α) and a "
      "Zemax BSDF file, with the surface's own glare spots in truth.json (docs/brdf.md)");
  sub->add_option("--surface", args->surface,
                  "standard (fitted to the paper's Table III), glare-reduced (Table VI), gaussian, "
                  "or a surface file FILE.toml (default standard)");
  sub->add_option("--out", args->out, "output directory")->required();
  sub->add_option("--format", args->format, "pabopto, zemax or both (default both)")
      ->check(CLI::IsMember({"pabopto", "zemax", "both"}))
      ->option_text("pabopto|zemax|both");
  sub->add_option("--alpha", args->alpha,
                  "angles of incidence in degrees, comma-separated (default 5,10,20,...,70: a lab "
                  "instrument's range)")
      ->option_text("DEG,...");
  sub->add_option("--noise", args->noise,
                  "relative standard deviation of each sample's noise (default 0.01)")
      ->check(CLI::Range(0.0, 0.49));
  sub->add_option("--fine-step", args->fine_step_deg,
                  "the step near the specular direction in degrees (default 0.1)")
      ->check(CLI::Range(0.01, 5.0));
  sub->add_option("--seed", args->seed, "the noise's seed (default 1)");
  sub->callback([args, &action] { action = [args] { return runSimulateBrdf(*args); }; });
}

}  // namespace glarecam::apps
