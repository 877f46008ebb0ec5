#include "surface/brdf_model.h"

#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "core/angles.h"
#include "surface/specular_frame.h"

namespace glarecam::surface {

double BrdfModel::brdfSr(const Ray& incident, const Ray& outgoing) const {
  if (!(incident.z > 0) || !(outgoing.z > 0)) return 0;
  return evaluate(incident, outgoing);
}

double BrdfModel::brdfSr(double incident_theta_deg, double incident_phi_deg,
                         double outgoing_theta_deg, double outgoing_phi_deg) const {
  return brdfSr(sampleDirection(incident_theta_deg, incident_phi_deg),
                sampleDirection(outgoing_theta_deg, outgoing_phi_deg));
}

Status GaussianLobeParameters::validate() const {
  if (!(peak_brdf_sr > 0 && std::isfinite(peak_brdf_sr)))
    return badInput("gaussian lobe: peak_brdf_sr must be positive");
  if (!(sigma_horizontal_deg > 0 && sigma_horizontal_deg < 30 && sigma_vertical_deg > 0 &&
        sigma_vertical_deg < 30))
    return badInput("gaussian lobe: the widths must be in (0, 30)°");
  if (!(floor_brdf_sr >= 0 && floor_brdf_sr < peak_brdf_sr))
    return badInput("gaussian lobe: floor_brdf_sr must be in [0, peak)");
  return {};
}

GaussianLobeBrdf::GaussianLobeBrdf(const GaussianLobeParameters& parameters)
    : parameters_(parameters) {}

std::string GaussianLobeBrdf::describe() const {
  return fmt::format("gaussian lobe: peak {:g} sr⁻¹, σ {:g}° × {:g}° (h × v), floor {:g} sr⁻¹",
                     parameters_.peak_brdf_sr, parameters_.sigma_horizontal_deg,
                     parameters_.sigma_vertical_deg, parameters_.floor_brdf_sr);
}

double GaussianLobeBrdf::evaluate(const Ray& incident, const Ray& outgoing) const {
  const auto [theta_i, phi_i] = sampleAngles(incident);
  const SpecularFrame frame(theta_i, phi_i);
  const calibration::Ray ray = frame.toFrame(outgoing);
  const calibration::PlanePointDeg p = calibration::AngularPlane(Ray{0, 0, 1}).toPlane(ray);
  const GaussianLobeParameters& g = parameters_;
  const double u = p.x_deg / g.sigma_horizontal_deg, v = p.y_deg / g.sigma_vertical_deg;
  return g.peak_brdf_sr * std::exp(-0.5 * (u * u + v * v)) + g.floor_brdf_sr;
}

const char* toString(SlopeDistribution distribution) {
  return distribution == SlopeDistribution::kBeckmann ? "beckmann" : "ggx";
}

std::optional<SlopeDistribution> slopeDistributionFromString(std::string_view text) {
  if (text == "beckmann") return SlopeDistribution::kBeckmann;
  if (text == "ggx") return SlopeDistribution::kGgx;
  return std::nullopt;
}

Status MicrofacetParameters::validate() const {
  constexpr double kMaxWidthDeg = 45;  // wider facets are no glass
  const auto width = [&](double w, const char* key) -> Status {
    if (!(w > 0 && w <= kMaxWidthDeg))
      return badInput(fmt::format("surface: {} {:g} must be in (0, {:g}]°", key, w, kMaxWidthDeg));
    return {};
  };
  GLARECAM_CHECK(width(width_x_deg, "width_x_deg"));
  GLARECAM_CHECK(width(width_y_deg, "width_y_deg"));
  GLARECAM_CHECK(width(second_lobe_width_deg, "second_lobe_width_deg"));
  constexpr double kMaxLobeWeight = 100;
  if (!(lobe_weight > 0 && lobe_weight <= kMaxLobeWeight))
    return badInput(fmt::format("surface: lobe_weight must be in (0, {:g}]", kMaxLobeWeight));
  if (!(refractive_index > 1 && refractive_index <= 3))
    return badInput("surface: refractive_index must be in (1, 3]");
  if (coating_index && !(*coating_index > 1 && *coating_index <= 3))
    return badInput("surface: coating_index must be in (1, 3]");
  if (!(coating_thickness_nm >= 0 && coating_thickness_nm <= 10'000))
    return badInput("surface: coating_thickness_nm must be in [0, 10000]");
  if (!(second_lobe_weight >= 0 && second_lobe_weight <= 1))
    return badInput("surface: second_lobe_weight must be in [0, 1]");
  if (!(diffuse_reflectance >= 0 && diffuse_reflectance <= 1))
    return badInput("surface: diffuse_reflectance must be in [0, 1]");
  return {};
}

double fresnelReflectance(double cos_incidence, const MicrofacetParameters& parameters) {
  using Complex = std::complex<double>;
  const double c0 = std::clamp(cos_incidence, 0.0, 1.0);
  const double s0 = std::sqrt(1 - c0 * c0);
  const double n2 = parameters.refractive_index;
  const auto cosIn = [&](double n) { return std::sqrt(std::max(0.0, 1 - (s0 / n) * (s0 / n))); };
  const double c2 = cosIn(n2);
  // Amplitude reflection coefficients between media j and k (s and p).
  const auto rs = [](double nj, double cj, double nk, double ck) {
    return (nj * cj - nk * ck) / (nj * cj + nk * ck);
  };
  const auto rp = [](double nj, double cj, double nk, double ck) {
    return (nk * cj - nj * ck) / (nk * cj + nj * ck);
  };
  if (!parameters.coating_index || parameters.coating_thickness_nm <= 0) {
    const double s = rs(1, c0, n2, c2), p = rp(1, c0, n2, c2);
    return 0.5 * (s * s + p * p);
  }
  // A thin film (Born & Wolf, Principles of Optics, §1.6.4): r = (r01 + r12 e^{2iδ}) /
  // (1 + r01 r12 e^{2iδ}), δ = 2π n1 d cos θ1 / λ.
  const double n1 = *parameters.coating_index, c1 = cosIn(n1);
  const double delta =
      2 * std::numbers::pi * n1 * parameters.coating_thickness_nm * c1 / kCoatingWavelengthNm;
  const Complex phase = std::polar(1.0, 2 * delta);
  const auto film = [&](double r01, double r12) {
    const Complex r = (r01 + r12 * phase) / (1.0 + r01 * r12 * phase);
    return std::norm(r);
  };
  return 0.5 * (film(rs(1, c0, n1, c1), rs(n1, c1, n2, c2)) +
                film(rp(1, c0, n1, c1), rp(n1, c1, n2, c2)));
}

namespace {

// The distribution's α from its width angle.
double alphaOf(double width_deg) { return std::tan(radians(width_deg)); }

double distribution(SlopeDistribution kind, const Ray& h, double ax, double ay) {
  const double x = h.x / ax, y = h.y / ay, z2 = h.z * h.z;
  if (kind == SlopeDistribution::kBeckmann) {
    return std::exp(-(x * x + y * y) / z2) / (std::numbers::pi * ax * ay * z2 * z2);
  }
  const double d = x * x + y * y + z2;
  return 1 / (std::numbers::pi * ax * ay * d * d);
}

// Smith's Λ for a direction w (Walter et al. 2007, eqs. 27 and 72; Heitz 2014 for the
// anisotropic α along w's azimuth).
double smithLambda(SlopeDistribution kind, const Ray& w, double ax, double ay) {
  const double sin2 = w.x * w.x + w.y * w.y;
  if (sin2 <= 0) return 0;
  const double alpha2 = (w.x * w.x * ax * ax + w.y * w.y * ay * ay) / sin2;
  const double tan2 = sin2 / (w.z * w.z);
  if (kind == SlopeDistribution::kGgx) return (-1 + std::sqrt(1 + alpha2 * tan2)) / 2;
  const double a = 1 / std::sqrt(alpha2 * tan2);
  return (std::erf(a) - 1) / 2 + std::exp(-a * a) / (2 * a * std::sqrt(std::numbers::pi));
}

}  // namespace

MicrofacetBrdf::MicrofacetBrdf(const MicrofacetParameters& parameters)
    : parameters_(parameters),
      alpha_x_(alphaOf(parameters.width_x_deg)),
      alpha_y_(alphaOf(parameters.width_y_deg)),
      alpha_2_(alphaOf(parameters.second_lobe_width_deg)) {}

std::string MicrofacetBrdf::describe() const {
  const MicrofacetParameters& p = parameters_;
  std::string text = fmt::format(
      "microfacet {}: widths {:.4g}° × {:.4g}° (x × y), lobe weight {:.4g}, n {:g}",
      toString(p.distribution), p.width_x_deg, p.width_y_deg, p.lobe_weight, p.refractive_index);
  if (p.coating_index)
    text += fmt::format(", AR coating n {:g} × {:g} nm", *p.coating_index, p.coating_thickness_nm);
  if (p.second_lobe_weight > 0)
    text +=
        fmt::format(", second lobe {:g} × {:g}°", p.second_lobe_weight, p.second_lobe_width_deg);
  if (p.diffuse_reflectance > 0) text += fmt::format(", diffuse {:g}", p.diffuse_reflectance);
  return text;
}

double MicrofacetBrdf::evaluate(const Ray& i, const Ray& o) const {
  Ray h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double norm = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
  if (!(norm > 0)) return 0;
  h = {h.x / norm, h.y / norm, h.z / norm};
  const MicrofacetParameters& p = parameters_;
  const double cos_ih = i.x * h.x + i.y * h.y + i.z * h.z;
  const double denominator = 4 * i.z * o.z;
  const SlopeDistribution kind = p.distribution;
  const double shadowing =
      1 / (1 + smithLambda(kind, i, alpha_x_, alpha_y_) + smithLambda(kind, o, alpha_x_, alpha_y_));
  double f = p.lobe_weight * distribution(kind, h, alpha_x_, alpha_y_) *
             fresnelReflectance(cos_ih, p) * shadowing / denominator;
  // The second lobe shadowed as the first (Smith, its own width): without it its 1/cos θ_o
  // diverges at grazing.
  if (p.second_lobe_weight > 0)
    f += p.second_lobe_weight * distribution(SlopeDistribution::kGgx, h, alpha_2_, alpha_2_) /
         (1 + smithLambda(SlopeDistribution::kGgx, i, alpha_2_, alpha_2_) +
          smithLambda(SlopeDistribution::kGgx, o, alpha_2_, alpha_2_)) /
         denominator;
  return f + p.diffuse_reflectance / std::numbers::pi;
}

}  // namespace glarecam::surface
