// The glare spot a surface model reflects, computed from the model alone (docs/brdf.md, "Truth"):
// the luminance L(o) = E · ⟨f_r(i, o) cos θ_i⟩ over the incident directions i of the sun's disc
// (E its direct normal illuminance, the mean over the disc's area: the convolution done as
// physics does it, by the incidence, not by shifting the picture), its peak, and the full axes of
// its contours at given levels, found by bisection along the plane of incidence through the peak
// (the vertical axis) and across it through the contour's centre (the horizontal axis). It never
// calls the glare analysis, so that the simulator's truth and the route check stay independent of
// what they test. The sun is in the sample's xz plane (φ_i = 0): a model symmetric about that
// plane has its axes along it and across it.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "core/error.h"
#include "surface/brdf_model.h"
#include "surface/specular_frame.h"
#include "surface/sun_disc.h"

namespace glarecam::surface {

struct LobeOptions {
  double illuminance_lx = 100'000;               // E (the reference sun)
  double sun_half_angle_deg = kSunHalfAngleDeg;  // the disc's radius; 0: a point source
  int disc_rings = 6;      // the disc's quadrature: 6 k points on ring k, equal areas
  double search_deg = 40;  // how far from the specular direction a contour is sought
};

// The luminance (cd/m²) reflected toward the angular-plane point `p` around the specular direction
// of the sun at `alpha_deg`.
double luminanceAt(const BrdfModel& model, double alpha_deg, const calibration::PlanePointDeg& p,
                   const LobeOptions& options = {});

struct ContourAxes {
  double level_cd_m2 = 0;
  // The full axes; none when the peak does not reach the level or the contour leaves the search.
  std::optional<double> vertical_deg, horizontal_deg;
};

struct LobeContours {
  double alpha_deg = 0;
  double peak_cd_m2 = 0;
  calibration::PlanePointDeg peak;  // where (on the plane of incidence)
  std::vector<ContourAxes> contours;
};

// The peak alone (on the plane of incidence), and one contour's axes around a found peak: what
// lobeContours() does for every level, for a caller that picks its levels from the peak.
LobeContours lobePeak(const BrdfModel& model, double alpha_deg, const LobeOptions& options = {});
ContourAxes contourAxes(const BrdfModel& model, const LobeContours& peak, double level_cd_m2,
                        const LobeOptions& options = {});

LobeContours lobeContours(const BrdfModel& model, double alpha_deg,
                          std::span<const double> levels_cd_m2, const LobeOptions& options = {});

}  // namespace glarecam::surface
