// The simulated goniophotometer (docs/brdf.md, "Simulated measurements"): a surface model
// (surface/brdf_model.h) measured as a lab measures it, for `glarecam simulate-brdf`, the tests
// and the route check. Its sampling is a lab's: rings around the specular direction, fine near it
// (`fine_step_deg` out to `fine_radius_deg`), medium out to `medium_radius_deg`, then a coarse
// θ/φ grid over the hemisphere; every value carries multiplicative Gaussian noise of the stated
// relative standard deviation (a fixed seed: the same files every run), which the pab-opto
// files state (#relative_noise). The lamp is a point source (a goniophotometer's is a fraction of
// a degree and is not deconvolved). Files: one pab-opto file per angle of incidence, and one
// Zemax BSDF file holding them all on its own grid (radial steps as the rings, azimuths every
// `azimuth_step_deg` over 0–180°: the models are symmetric about the plane of incidence).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdf/brdf_file.h"
#include "brdf/brdf_measurement.h"
#include "core/error.h"
#include "surface/brdf_model.h"

namespace glarecam::brdf {

struct GoniophotometerOptions {
  // Lab instruments stop at about 70° (the sample's holder shades the beam beyond).
  std::vector<double> alphas_deg = {5, 10, 20, 30, 40, 50, 60, 70};
  double fine_step_deg = 0.1, fine_radius_deg = 5;
  double medium_step_deg = 1, medium_radius_deg = 30;
  double coarse_step_deg = 5;
  double azimuth_step_deg = 2;  // the Zemax grid's
  double relative_noise = 0.01;
  std::uint64_t seed = 1;
  std::string sample_name = "simulated";
  Status validate() const;
};

// One angle of incidence measured (file name `file` in the measurement).
BrdfMeasurement simulateMeasurement(const surface::BrdfModel& model, double alpha_deg,
                                    const GoniophotometerOptions& options, const std::string& file);

// Every angle of incidence on the Zemax grid.
ZemaxTable simulateZemaxTable(const surface::BrdfModel& model,
                              const GoniophotometerOptions& options);

struct SimulatedFiles {
  std::vector<std::filesystem::path> pabopto;  // one per α
  std::filesystem::path zemax;                 // empty when not written
  std::filesystem::path truth;                 // truth.json
};

// The surface's own glare spot per α under the reference sun (surface/lobe_contours.h, never
// the analysis): Lmax and the limit and half-maximum axes, as truth.json holds them.
nlohmann::json surfaceTruth(const surface::BrdfModel& model, const std::vector<double>& alphas_deg,
                            double reference_illuminance_lx, double sun_half_angle_deg);

enum class SimulatedFormats { kPabOpto, kZemax, kBoth };

// Writes the files into `directory` (made when missing), each atomically: a<α>.dat,
// surface.bsdf and truth.json (surfaceTruth() at 100 klx under the sun's disc, and the model).
Result<SimulatedFiles> writeSimulatedMeasurements(const surface::BrdfModel& model,
                                                  const GoniophotometerOptions& options,
                                                  SimulatedFormats formats,
                                                  const std::filesystem::path& directory);

}  // namespace glarecam::brdf
