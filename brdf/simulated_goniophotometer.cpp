#include "brdf/simulated_goniophotometer.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>

#include "brdf/brdf_luminance.h"
#include "core/atomic_file.h"
#include "core/json.h"
#include "pipeline/limit_curve.h"
#include "surface/lobe_contours.h"
#include "surface/specular_frame.h"

namespace glarecam::brdf {

namespace fs = std::filesystem;
using surface::SpecularFrame;

Status GoniophotometerOptions::validate() const {
  if (alphas_deg.empty()) return badInput("simulate-brdf: no angles of incidence");
  for (std::size_t i = 1; i < alphas_deg.size(); ++i)
    if (!(alphas_deg[i] > alphas_deg[i - 1]))
      return badInput(
          fmt::format("simulate-brdf: --alpha must ascend, each angle once ({:g}° after {:g}°)",
                      alphas_deg[i], alphas_deg[i - 1]));
  for (double alpha : alphas_deg)
    if (!(alpha >= 0 && alpha <= kMaxIncidentThetaDeg))
      return badInput(
          fmt::format("simulate-brdf: α {:g}° is outside [0, {:g}]°", alpha, kMaxIncidentThetaDeg));
  if (!(fine_step_deg >= 0.01 && fine_step_deg <= fine_radius_deg &&
        fine_radius_deg <= medium_radius_deg && medium_step_deg >= fine_step_deg &&
        medium_radius_deg <= 80 && coarse_step_deg >= medium_step_deg && coarse_step_deg <= 30))
    return badInput(
        "simulate-brdf: the steps must grow outward (0.01° <= fine <= medium <= coarse <= 30°) and "
        "the radii too (fine <= medium <= 80°)");
  if (!(azimuth_step_deg >= 0.1 && azimuth_step_deg <= 30))
    return badInput("simulate-brdf: the azimuth step must be in [0.1, 30]°");
  if (!(relative_noise >= 0 && relative_noise < 0.5))
    return badInput("simulate-brdf: --noise must be in [0, 0.5)");
  return {};
}

namespace {

// The radii of the rings: fine steps out to the fine radius, medium ones beyond.
std::vector<double> ringRadii(const GoniophotometerOptions& o) {
  std::vector<double> radii;
  for (int k = 0; k * o.fine_step_deg <= o.fine_radius_deg + 1e-9; ++k)
    radii.push_back(k * o.fine_step_deg);
  for (double r = radii.back() + o.medium_step_deg; r <= o.medium_radius_deg + 1e-9;
       r += o.medium_step_deg)
    radii.push_back(r);
  return radii;
}

std::mt19937_64 generatorFor(const GoniophotometerOptions& o, double alpha_deg) {
  return std::mt19937_64(o.seed * 1'000'003 + static_cast<std::uint64_t>(alpha_deg * 1000));
}

double noisy(double value, std::normal_distribution<double>& noise, std::mt19937_64& random) {
  return std::max(0.0, value * (1 + noise(random)));
}

}  // namespace

BrdfMeasurement simulateMeasurement(const surface::BrdfModel& model, double alpha_deg,
                                    const GoniophotometerOptions& o, const std::string& file) {
  BrdfMeasurement m;
  m.file = file;
  m.format = BrdfFileFormat::kPabOpto;
  m.sample_name = o.sample_name;
  m.incident_theta_deg = alpha_deg;
  m.incident_phi_deg = 0;
  m.relative_noise = o.relative_noise;
  std::mt19937_64 random = generatorFor(o, alpha_deg);
  std::normal_distribution<double> noise(0.0, o.relative_noise > 0 ? o.relative_noise : 1e-300);
  const SpecularFrame frame(alpha_deg, 0);
  const calibration::Ray incident = surface::sampleDirection(alpha_deg, 0);
  const auto add = [&](double theta, double phi) {
    const double f = model.brdfSr(incident, surface::sampleDirection(theta, phi));
    m.samples.push_back({theta, phi, o.relative_noise > 0 ? noisy(f, noise, random) : f, 0});
  };
  // Rings around the specular direction, a sample every step along each.
  const std::vector<double> radii = ringRadii(o);
  for (std::size_t k = 0; k < radii.size(); ++k) {
    const double rho = radii[k];
    const double step = rho <= o.fine_radius_deg + 1e-9 ? o.fine_step_deg : o.medium_step_deg;
    const int n =
        rho == 0 ? 1 : std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * rho / step)));
    for (int j = 0; j < n; ++j) {
      const double psi = 2 * std::numbers::pi * j / n;
      const auto [theta, phi] = frame.fromPlane({rho * std::cos(psi), rho * std::sin(psi)});
      constexpr double kMaxThetaDeg = 89;  // the instrument's detector cannot graze the sample
      if (theta <= kMaxThetaDeg) add(theta, phi);
    }
  }
  // The hemisphere beyond, coarsely.
  for (double theta = 0; theta <= 85 + 1e-9; theta += o.coarse_step_deg)
    for (double phi = 0; phi < 360 - 1e-9; phi += theta == 0 ? 360 : o.coarse_step_deg) {
      const calibration::PlanePointDeg p = frame.toPlane(theta, phi);
      if (std::hypot(p.x_deg, p.y_deg) > o.medium_radius_deg) add(theta, phi);
    }
  return m;
}

ZemaxTable simulateZemaxTable(const surface::BrdfModel& model, const GoniophotometerOptions& o) {
  ZemaxTable table;
  table.source = "Measured";  // as a lab writes it: these are the simulator's stand-in
  table.plane_symmetric = true;
  table.radial_deg = ringRadii(o);
  for (double a = 0; a <= 180 + 1e-9; a += o.azimuth_step_deg) table.azimuth_deg.push_back(a);
  if (table.azimuth_deg.back() < 180) table.azimuth_deg.push_back(180);
  for (double alpha : o.alphas_deg) {
    std::mt19937_64 random = generatorFor(o, alpha + 0.5);
    std::normal_distribution<double> noise(0.0, o.relative_noise > 0 ? o.relative_noise : 1e-300);
    const SpecularFrame frame(alpha, 0);
    const calibration::Ray incident = surface::sampleDirection(alpha, 0);
    ZemaxTable::Block block;
    block.incident_theta_deg = alpha;
    for (double azimuth : table.azimuth_deg)
      for (double radial : table.radial_deg) {
        const calibration::Ray out = frame.sampleRay(zemaxScatterRay(radial, azimuth));
        // The detector cannot graze the sample: nothing is measured beyond 89° (a Zemax grid's
        // directions there hold 0, as instruments write them).
        constexpr double kMaxMeasuredCos = 0.0174524;  // cos 89°
        const double f = out.z > kMaxMeasuredCos ? model.brdfSr(incident, out) : 0.0;
        block.values.push_back(o.relative_noise > 0 ? noisy(f, noise, random) : f);
      }
    table.blocks.push_back(std::move(block));
  }
  return table;
}

nlohmann::json surfaceTruth(const surface::BrdfModel& model, const std::vector<double>& alphas_deg,
                            double reference_illuminance_lx, double sun_half_angle_deg) {
  const surface::LobeOptions lobe{.illuminance_lx = reference_illuminance_lx,
                                  .sun_half_angle_deg = sun_half_angle_deg};
  const auto axes = [](const surface::ContourAxes& c) -> nlohmann::json {
    if (!c.vertical_deg || !c.horizontal_deg) return nullptr;
    return {{"level_cd_m2", c.level_cd_m2},
            {"vertical_deg", *c.vertical_deg},
            {"horizontal_deg", *c.horizontal_deg}};
  };
  nlohmann::json rows = nlohmann::json::array();
  for (double alpha : alphas_deg) {
    const std::optional<double> limit = pipeline::glareLimitCdM2(alpha);
    std::vector<double> levels;
    if (limit) levels.push_back(*limit);
    const surface::LobeContours at_limit = surface::lobeContours(model, alpha, levels, lobe);
    const double half[] = {at_limit.peak_cd_m2 / 2};
    const surface::LobeContours at_half = surface::lobeContours(model, alpha, half, lobe);
    rows.push_back({{"alpha_deg", alpha},
                    {"lmax_cd_m2", at_limit.peak_cd_m2},
                    {"limit", limit ? axes(at_limit.contours[0]) : nlohmann::json(nullptr)},
                    {"fwhm", axes(at_half.contours[0])}});
  }
  return {{"surface", model.describe()},
          {"reference_illuminance_lx", reference_illuminance_lx},
          {"sun_half_angle_deg", sun_half_angle_deg},
          {"computed", "surface/lobe_contours.h: bisection on the model, not the glare analysis"},
          {"angles", rows}};
}

Result<SimulatedFiles> writeSimulatedMeasurements(const surface::BrdfModel& model,
                                                  const GoniophotometerOptions& options,
                                                  SimulatedFormats formats,
                                                  const fs::path& directory) {
  GLARECAM_CHECK(options.validate());
  GLARECAM_CHECK(ensureDirectory(directory));
  SimulatedFiles files;
  if (formats != SimulatedFormats::kZemax) {
    for (double alpha : options.alphas_deg) {
      const fs::path path = directory / fmt::format("a{:02g}.dat", alpha);
      const BrdfMeasurement m = simulateMeasurement(model, alpha, options, path.string());
      GLARECAM_CHECK(writeFileAtomic(path, formatPabOpto(m)));
      files.pabopto.push_back(path);
    }
  }
  if (formats != SimulatedFormats::kPabOpto) {
    files.zemax = directory / "surface.bsdf";
    GLARECAM_CHECK(
        writeFileAtomic(files.zemax, formatZemaxBsdf(simulateZemaxTable(model, options))));
  }
  files.truth = directory / "truth.json";
  nlohmann::json truth =
      surfaceTruth(model, options.alphas_deg, kDefaultReferenceIlluminanceLx, kSunHalfAngleDeg);
  truth["relative_noise"] = options.relative_noise;
  GLARECAM_CHECK(writeJsonFile(files.truth, truth));
  return files;
}

}  // namespace glarecam::brdf
