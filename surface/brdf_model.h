// Physical surface models of a module's front glass (docs/brdf.md, "The surface model"): what the
// simulated camera and the simulated goniophotometer render, and what `glarecam model fit` fits
// to a sweep of either route. The base class owns the contract: directions are unit vectors of
// the sample's frame (surface/specular_frame.h), the incident one toward the source; f_r is in
// sr⁻¹, finite and >= 0, and 0 for either direction at or below the surface.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "calibration/camera_model.h"
#include "core/error.h"

namespace glarecam::surface {

using calibration::Ray;

class BrdfModel {
 public:
  virtual ~BrdfModel() = default;
  double brdfSr(const Ray& incident, const Ray& outgoing) const;
  double brdfSr(double incident_theta_deg, double incident_phi_deg, double outgoing_theta_deg,
                double outgoing_phi_deg) const;
  virtual std::string describe() const = 0;

 protected:
  // Both directions above the surface (z > 0), unit length.
  virtual double evaluate(const Ray& incident, const Ray& outgoing) const = 0;
};

// An elliptical Gaussian lobe drawn in the angular plane around the specular direction, whatever
// the incidence: f = peak · exp(-x²/2σh² - y²/2σv²) + floor. Not a physical surface: the analytic
// case the route's tests check against (its contours are known in closed form before the sun's
// disc, and computed independently after it).
struct GaussianLobeParameters {
  double peak_brdf_sr = 100;
  double sigma_horizontal_deg = 2, sigma_vertical_deg = 1.5;
  double floor_brdf_sr = 0;
  Status validate() const;
};

class GaussianLobeBrdf : public BrdfModel {
 public:
  explicit GaussianLobeBrdf(const GaussianLobeParameters& parameters);
  std::string describe() const override;
  const GaussianLobeParameters& parameters() const { return parameters_; }

 protected:
  double evaluate(const Ray& incident, const Ray& outgoing) const override;

 private:
  GaussianLobeParameters parameters_;
};

// The facets' slope distribution (Walter et al. 2007, "Microfacet models for refraction through
// rough surfaces", EGSR): Beckmann (Gaussian slopes) or GGX (Trowbridge–Reitz, longer tails).
enum class SlopeDistribution { kBeckmann, kGgx };
const char* toString(SlopeDistribution distribution);  // "beckmann", "ggx"
std::optional<SlopeDistribution> slopeDistributionFromString(std::string_view text);

// A microfacet BRDF of the front glass (docs/brdf.md): facets of a slope distribution with two
// widths (along the sample's x and y: a directional texture when they differ), reflecting by
// Fresnel at the glass (with an optional single-layer anti-reflective coating), shadowed by
// Smith's height-correlated term; plus a broad second lobe (the rear interfaces of textured
// glass) and a Lambertian floor.
struct MicrofacetParameters {
  SlopeDistribution distribution = SlopeDistribution::kGgx;
  // The widths as angles: atan of the distribution's α along x and y (Beckmann: α = √2 · rms
  // slope; GGX: α of Walter et al.).
  double width_x_deg = 1.5, width_y_deg = 1.5;
  // The share of the glass whose facets make the narrow lobe (the rest: a rougher population,
  // the second lobe, the floor). Above 1 it is no share but the statement that the lobe is
  // brighter than glass of this index under the reference sun can make it (docs/brdf.md).
  double lobe_weight = 1;
  // Soda-lime solar glass at 550 nm (Rubin 1985, "Optical properties of soda lime silica
  // glasses", Sol. Energy Mater. 12: n = 1.52).
  double refractive_index = 1.52;
  // A single-layer AR coating: its index and thickness (none when the index is unset). Porous
  // silica, the common solar AR coating: n ≈ 1.25–1.30, a quarter wave at 550 nm ≈ 110 nm.
  std::optional<double> coating_index = std::nullopt;
  double coating_thickness_nm = 0;
  // The broad second lobe: a GGX of this width, weighted (its own Fresnel and transmission folded
  // into the weight, a fraction of the reflected light); 0: none.
  double second_lobe_weight = 0, second_lobe_width_deg = 10;
  double diffuse_reflectance = 0;  // the Lambertian floor's ρ_d (f = ρ_d / π)
  Status validate() const;
};

// The wavelength the coating's phase is computed at: the photopic peak (CIE V(λ) at 555 nm,
// rounded as solar AR coatings are specified).
inline constexpr double kCoatingWavelengthNm = 550.0;

// Unpolarised Fresnel reflectance of the glass (with its coating) at `cos_incidence` from air.
double fresnelReflectance(double cos_incidence, const MicrofacetParameters& parameters);

class MicrofacetBrdf : public BrdfModel {
 public:
  explicit MicrofacetBrdf(const MicrofacetParameters& parameters);
  std::string describe() const override;
  const MicrofacetParameters& parameters() const { return parameters_; }

 protected:
  double evaluate(const Ray& incident, const Ray& outgoing) const override;

 private:
  MicrofacetParameters parameters_;
  double alpha_x_, alpha_y_, alpha_2_;
};

}  // namespace glarecam::surface
