#include "surface/brdf_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/angles.h"
#include "surface/specular_frame.h"

namespace glarecam::surface {
namespace {

TEST(Fresnel, NormalIncidenceOnGlassIsTheTextbookValue) {
  // ((n - 1) / (n + 1))² at n = 1.52: 4.26 %.
  MicrofacetParameters glass;
  EXPECT_NEAR(fresnelReflectance(1.0, glass), std::pow(0.52 / 2.52, 2), 1e-12);
  // Grazing: total reflection.
  EXPECT_NEAR(fresnelReflectance(0.0, glass), 1.0, 1e-9);
}

TEST(Fresnel, AQuarterWaveCoatingOfTheRootIndexCancelsTheNormalReflection) {
  // A film of index √n and optical thickness λ/4 is the ideal single-layer AR coating: R(0) = 0
  // (Born & Wolf §1.6.4); a porous-silica one (1.27) leaves a fraction of a per cent.
  MicrofacetParameters ideal;
  ideal.coating_index = std::sqrt(ideal.refractive_index);
  ideal.coating_thickness_nm = kCoatingWavelengthNm / (4 * *ideal.coating_index);
  EXPECT_NEAR(fresnelReflectance(1.0, ideal), 0.0, 1e-12);
  MicrofacetParameters silica = ideal;
  silica.coating_index = 1.27;
  silica.coating_thickness_nm = kCoatingWavelengthNm / (4 * 1.27);
  EXPECT_LT(fresnelReflectance(1.0, silica), 0.01);
  EXPECT_GT(fresnelReflectance(1.0, silica), 0.0);
}

TEST(MicrofacetBrdf, IsReciprocalAndZeroBelowTheSurface) {
  MicrofacetParameters p;
  p.width_x_deg = 2;
  p.width_y_deg = 1;
  p.second_lobe_weight = 0.1;
  p.diffuse_reflectance = 0.01;
  for (SlopeDistribution kind : {SlopeDistribution::kGgx, SlopeDistribution::kBeckmann}) {
    p.distribution = kind;
    const MicrofacetBrdf brdf(p);
    const double forward = brdf.brdfSr(40, 0, 38, 178);
    EXPECT_GT(forward, 0);
    EXPECT_NEAR(brdf.brdfSr(38, 178, 40, 0), forward, 1e-12 * forward);  // Helmholtz
    EXPECT_EQ(brdf.brdfSr(40, 0, 95, 180), 0.0);
  }
}

TEST(MicrofacetBrdf, NarrowFacetsReflectTheFresnelFractionOfTheLight) {
  // Integrated over the hemisphere, ∫ f cos θ_o dω is the reflected fraction: for narrow facets
  // Fresnel's at the incidence (shadowing negligible at 30°). The integral runs over the angular
  // plane around the specular direction, ±10°, 0.01° cells: Beckmann facets of α = tan 1° have
  // all but 1e-20 of their normals within the 5° it holds (GGX's tails would leave 4 % outside).
  MicrofacetParameters p;
  p.distribution = SlopeDistribution::kBeckmann;
  p.width_x_deg = p.width_y_deg = 1;
  const MicrofacetBrdf brdf(p);
  const SpecularFrame frame(30, 0);
  const calibration::Ray incident = sampleDirection(30, 0);
  double sum = 0;
  constexpr double kCellDeg = 0.01, kHalfDeg = 10;
  for (double x = -kHalfDeg; x <= kHalfDeg; x += kCellDeg)
    for (double y = -kHalfDeg; y <= kHalfDeg; y += kCellDeg) {
      const calibration::Ray o = frame.sampleRayAt({x, y});
      // The azimuthal-equidistant cell's solid angle: sin ρ / ρ of the flat one.
      const double rho = radians(std::hypot(x, y));
      const double jacobian = rho > 0 ? std::sin(rho) / rho : 1.0;
      sum += brdf.brdfSr(incident, o) * o.z * jacobian * radians(kCellDeg) * radians(kCellDeg);
    }
  // The facets' normals spread 1°, so Fresnel varies by far less than the 1 % allowed here.
  EXPECT_NEAR(sum, fresnelReflectance(std::cos(radians(30)), p), 0.01 * sum);
}

TEST(GaussianLobeBrdf, IsTheGivenLobeAroundTheSpecularDirection) {
  const GaussianLobeBrdf lobe({.peak_brdf_sr = 50,
                               .sigma_horizontal_deg = 2,
                               .sigma_vertical_deg = 1,
                               .floor_brdf_sr = 0.1});
  const SpecularFrame frame(25, 0);
  const calibration::Ray incident = sampleDirection(25, 0);
  EXPECT_NEAR(lobe.brdfSr(incident, frame.sampleRayAt({0, 0})), 50.1, 1e-9);
  EXPECT_NEAR(lobe.brdfSr(incident, frame.sampleRayAt({2, 0})), 50 * std::exp(-0.5) + 0.1, 1e-9);
  EXPECT_NEAR(lobe.brdfSr(incident, frame.sampleRayAt({0, 1})), 50 * std::exp(-0.5) + 0.1, 1e-9);
}

TEST(Parameters, RefuseWhatNoGlassIs) {
  MicrofacetParameters p;
  p.width_x_deg = 0;
  EXPECT_FALSE(p.validate());
  p = {};
  p.refractive_index = 0.9;
  EXPECT_FALSE(p.validate());
  p = {};
  p.second_lobe_weight = 2;
  EXPECT_FALSE(p.validate());
  EXPECT_TRUE(MicrofacetParameters{}.validate());
  EXPECT_FALSE((GaussianLobeParameters{.peak_brdf_sr = -1}.validate()));
}

}  // namespace
}  // namespace glarecam::surface
