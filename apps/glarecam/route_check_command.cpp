// glarecam route-check: one surface through both of the method's routes, compared in σ
// (docs/brdf.md, "The route check").

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "brdf/route_check.h"
#include "core/json.h"

namespace glarecam::apps {
namespace {

struct RouteCheckArgs {
  brdf::RouteCheckOptions options;
  std::optional<std::string> alpha, out;
  std::string size = "640x512";
  std::string seed = "1";
  bool no_progress = false, json = false, markdown = false;
};

Status runRouteCheck(RouteCheckArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  if (args.out) args.options.output_directory = *args.out;
  if (args.alpha)
    GLARECAM_ASSIGN(args.options.alphas_deg, parseNumberList(*args.alpha, "--alpha", 1, 90));
  GLARECAM_ASSIGN(std::tie(args.options.width, args.options.height),
                  parseSize(args.size, "--size"));
  GLARECAM_ASSIGN(args.options.seed, parseUnsigned(args.seed, "--seed"));
  args.options.show_progress = !args.no_progress;
  brdf::RouteCheckSummary summary;
  GLARECAM_ASSIGN(summary, brdf::runRouteCheck(args.options));
  const std::string threshold =
      fmt::format("{:.2f}σ{}", summary.threshold_z,
                  args.options.agreement_z ? "" : " (3σ for the whole check)");
  const std::string verdict =
      summary.compared == 0
          ? fmt::format("route-check: {}: nothing compared (every row says why): no agreement",
                        summary.surface)
          : fmt::format("route-check: {}: {} quantities compared, worst |z| {:.2f} ({}): {} {}",
                        summary.surface, summary.compared, summary.worst_abs_z, summary.worst,
                        summary.agree ? "the routes agree within" : "BEYOND", threshold);
  if (args.json) {
    printJson(brdf::routeCheckJson(summary, args.options));
  } else if (args.markdown) {
    std::fputs(brdf::formatRouteCheckMarkdown(summary).c_str(), stdout);
  } else {
    for (const brdf::RouteCheckRow& row : summary.rows) {
      const auto z = [](const brdf::RouteQuantity& q) {
        return q.z ? fmt::format("{:+5.1f}σ", *q.z) : std::string("    –");
      };
      const bool beyond = row.compared() && !row.agrees(summary.threshold_z);
      std::string line =
          fmt::format("α {:5.1f}°  Lmax {}  vertical {}  horizontal {}", row.alpha_deg,
                      z(row.lmax_cd_m2), z(row.vertical_deg), z(row.horizontal_deg));
      if (beyond) line += "  BEYOND " + threshold;
      if (!row.note.empty()) line += "  " + row.note;
      std::printf("%s\n", line.c_str());
    }
    if (summary.agree) std::printf("%s\n", verdict.c_str());
    std::printf("%s\n", summary.csv.c_str());
  }
  if (!summary.agree) return fail(ErrorCode::kInternal, verdict);
  return {};
}

}  // namespace

void addRouteCheckCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<RouteCheckArgs>();
  brdf::RouteCheckOptions& o = args->options;
  CLI::App* sub = app.add_subcommand(
      "route-check",
      "One surface through both of the method's routes (the simulated camera under the sun, the "
      "simulated goniophotometer and the BRDF route): Lmax and the limit axes per α compared in "
      "units of their combined uncertainty, beside the surface's truth; exit 1 when they "
      "disagree (docs/brdf.md)");
  sub->add_option("--surface", o.surface,
                  "standard, glare-reduced, gaussian or a surface file FILE.toml")
      ->capture_default_str();
  sub->add_option("--out", args->out,
                  "output directory: camera/, goniophotometer/, brdf/, route-check.csv and "
                  "route-check.json (default ./route-check)");
  sub->add_option(
         "--alpha", args->alpha,
         "angles of incidence in degrees, ascending, comma-separated (default 5,10,...,80)")
      ->option_text("DEG,...");
  sub->add_option("--size", args->size,
                  "the simulated camera's frame WIDTHxHEIGHT, 64x64 to 4096x4096 (a GGX tip a few "
                  "pixels across reads low: keep 16 px a degree, docs/brdf.md)")
      ->capture_default_str();
  sub->add_option("--fov", o.horizontal_fov_deg,
                  "the simulated camera's horizontal field of view, 5 to 120 degrees")
      ->capture_default_str();
  sub->add_option("--seed", args->seed,
                  "the camera's noise seed at the first α (then +1 per α), a whole number >= 0")
      ->capture_default_str()
      ->type_name("UINT");
  sub->add_option("--fine-step", o.goniophotometer.fine_step_deg,
                  "the goniophotometer's step near the specular direction, degrees (0.01 to 5)")
      ->capture_default_str();
  sub->add_option("--noise", o.goniophotometer.relative_noise,
                  "the goniophotometer's relative noise per sample, [0, 0.5)")
      ->capture_default_str();
  sub->add_option("--instrument-max-alpha", o.instrument_max_alpha_deg,
                  "the largest α the goniophotometer measures, degrees")
      ->capture_default_str();
  sub->add_option("--agreement", o.agreement_z,
                  "the routes agree when every |z| is at most this many σ (default: 3σ for the "
                  "whole check, Šidák-corrected for the number of comparisons: 4.0 for 40)")
      ->option_text("Z");
  auto* markdown =
      sub->add_flag("--markdown", args->markdown, "print the table as Markdown (docs/brdf.md's)");
  sub->add_flag("--json", args->json, "print route-check.json on stdout")->excludes(markdown);
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runRouteCheck(*args); }; });
}

}  // namespace glarecam::apps
