// glarecam brdf: goniophotometer files -> the BRDF route's results, sweep.csv and contours.csv
// (docs/brdf.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "brdf/brdf_route.h"

namespace glarecam::apps {
namespace {

struct BrdfArgs {
  std::vector<std::string> files;
  std::optional<std::string> out, reference_illuminance, threshold;
  double source_radius_deg = brdf::kSunHalfAngleDeg;
  double half_width_deg = 20;
  int size_px = 801;
  bool no_progress = false, no_ladder = false, float32 = false, json = false;
};

Status runBrdf(const BrdfArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  brdf::BrdfRouteOptions options;
  if (args.out) options.output_directory = *args.out;
  GLARECAM_ASSIGN(options.image.reference_illuminance_lx,
                  parseReferenceIlluminance(args.reference_illuminance, "--reference-illuminance"));
  GLARECAM_ASSIGN(options.threshold_cd_m2, parseOptionalLuminance(args.threshold, "--threshold"));
  options.image.sun_half_angle_deg = args.source_radius_deg;
  options.image.max_half_width_deg = args.half_width_deg;
  options.image.max_size_px = args.size_px;
  options.ladder = !args.no_ladder;
  options.float32 = args.float32;
  options.show_progress = !args.no_progress;
  std::vector<std::filesystem::path> files;
  for (const std::string& file : args.files) {
    if (file.empty()) return badInput("FILES: expected a path, got an empty string");
    files.emplace_back(file);
  }
  brdf::BrdfRouteSummary summary;
  GLARECAM_ASSIGN(summary, brdf::runBrdfRoute(files, options));
  for (const brdf::BrdfAngle& angle : summary.angles) {
    const pipeline::StackResult& r = angle.result;
    const auto& limit = r.limit.ellipse;
    spdlog::info(
        "brdf: α {:g}°: Lmax {:.4g} cd/m², limit ellipse {}", *r.alpha_deg, r.luminance.max_cd_m2,
        limit ? fmt::format("{:.2f}° × {:.2f}°", limit->vertical_deg, limit->horizontal_deg)
              : std::string("none"));
  }
  if (args.json) {
    nlohmann::json angles = nlohmann::json::array();
    for (const brdf::BrdfAngle& angle : summary.angles)
      angles.push_back({{"result", angle.result_directory.string()},
                        {"alpha_deg", *angle.result.alpha_deg},
                        {"warnings", angle.warnings}});
    printJson({{"sweep_csv", summary.sweep_csv.string()},
               {"contours_csv", summary.contours_csv.string()},
               {"angles", angles}});
    return {};
  }
  std::printf("%s\n", summary.sweep_csv.c_str());
  return {};
}

}  // namespace

void addBrdfCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<BrdfArgs>();
  CLI::App* sub = app.add_subcommand(
      "brdf",
      "The BRDF route: goniophotometer files (pab-opto/Radiance or Zemax BSDF text) -> the "
      "luminance under the reference sun, its glare ellipses, sweep.csv and contours.csv "
      "(docs/brdf.md)");
  sub->add_option("FILES", args->files,
                  "BRDF files: one pab-opto file per angle of incidence, or Zemax BSDF files "
                  "(several angles each)")
      ->required();
  sub->add_option("--out", args->out,
                  "output directory for sweep.csv, contours.csv and results/<file>/ (default "
                  "./brdf)");
  sub->add_option("--reference-illuminance", args->reference_illuminance,
                  std::string(kReferenceIlluminanceHelp) +
                      ": the sun the luminance is computed under, L = f_r · E_ref · cos α")
      ->option_text("LX");
  sub->add_option("--threshold", args->threshold,
                  "constant glare limit in cd/m² instead of the α curve (e.g. 30000)");
  sub->add_option("--source-radius", args->source_radius_deg,
                  "angular radius in degrees of the source the BRDF is convolved with (default "
                  "0.2664: the sun's disc; 0: a point source)")
      ->check(CLI::Range(0.0, 5.0));
  sub->add_option("--half-width", args->half_width_deg,
                  "the picture's half width in degrees around the specular direction, at most "
                  "(default 20; less where the samples stop)")
      ->check(CLI::Range(1.0, 60.0));
  sub->add_option("--pixels", args->size_px,
                  "the picture's pixels across, at most (odd; default 801)")
      ->check(CLI::Range(65, 4001));
  sub->add_flag("--no-ladder", args->no_ladder, "no contour ladder (result.json contours null)");
  sub->add_flag("--float32", args->float32,
                "each result's images in lossless float32 (as process --float32)");
  sub->add_flag("--json", args->json, "print the outputs as JSON on stdout");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runBrdf(*args); }; });
}

}  // namespace glarecam::apps
