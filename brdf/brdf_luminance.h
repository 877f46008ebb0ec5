// The luminance picture of a BRDF measurement under the reference sun (docs/method.md "Relation
// to the BRDF", docs/brdf.md): L(ω_r) = f_r(ω_i, ω_r) · E_ref · cos θ_i, convolved with the
// solar disc, in the angular plane around the specular direction, and seen by a pinhole camera
// looking along it, so that the camera route's glare analysis measures it unchanged.
//
// The steps: the samples go to the angular plane (SpecularFrame); a Delaunay triangulation
// interpolates ln f_r linearly onto a square grid (the largest around the specular direction
// that the samples cover, at most `max_half_width_deg`); the grid is convolved with the sun's
// uniform disc (radius kSunHalfAngleDeg; 0 for a point source); the pinhole image takes each
// pixel's ray from the grid (bilinear). Every pixel's relative uncertainty is the data's noise
// (stated by the file or estimated: brdf_measurement.h), scaled up for its correlation over a
// sample spacing; the grid's interpolation error, alike over the lobe's top, is stated apart
// (grid_relative_uncertainty) for the route to carry as the picture's scale uncertainty.
#pragma once

#include "brdf/brdf_measurement.h"
#include "calibration/hdr_merge.h"
#include "core/source_illuminance.h"
#include "core/stack_manifest.h"
#include "surface/sun_disc.h"

namespace glarecam::brdf {

using surface::discKernel;
using surface::kSunHalfAngleDeg;

// The noise assumed when the file states none and the data are too few to estimate it.
inline constexpr double kAssumedRelativeNoise = 0.02;

struct LuminanceImageOptions {
  double reference_illuminance_lx = kDefaultReferenceIlluminanceLx;  // E_ref
  double sun_half_angle_deg = kSunHalfAngleDeg;  // 0: no convolution (a point source)
  double max_half_width_deg = 20;                // the picture's half width at most
  int max_size_px = 801;        // its pixels across at most (odd: a pixel on the specular ray)
  double min_pixel_deg = 0.01;  // its pixels no finer than this
  Status validate() const;
};

struct BrdfLuminance {
  calibration::MergedImage image;  // cd/m² under E_ref; relative uncertainty
  Intrinsics intrinsics;           // the pinhole camera of the picture
  double pixel_deg = 0;            // at the centre
  double half_width_deg = 0;       // of the grid
  double covered_deg = 0;          // the samples' coverage around the specular direction
  double relative_noise = 0;
  std::string noise_origin;  // "stated", "estimated" or "assumed"
  // Pixels a sample spacing spans (at least 1): the per-pixel uncertainty is the noise times it.
  double noise_correlation = 1;
  // The grid's share: linear interpolation of ln f between samples h apart under-reads a lobe
  // of σ by up to h²/8σ² (at the narrower σ). The under-read is one-sided and not corrected, so
  // its whole bound is the standard uncertainty (GUM F.2.4.5: an uncorrected known bias belongs
  // in the uncertainty whole); the route check measured it at 0.2 % (α 20°) and 0.8 % (α 70°)
  // for a bound of 0.19 % and 1.06 % at 0.1° steps (docs/brdf.md).
  double grid_relative_uncertainty = 0;  // at the peak: the median spacing on the lobe
  // The same at the coarsest spacing on the lobe (≥ ¼ of the peak), where a lab's rings widen
  // and the contours may lie: what the fixed levels' ellipses inherit.
  double contour_grid_relative_uncertainty = 0;
};

// Needs `sampling` from checkSampling() of the same measurement.
Result<BrdfLuminance> luminanceUnderSun(const BrdfMeasurement& measurement,
                                        const SamplingCheck& sampling,
                                        const LuminanceImageOptions& options = {});

}  // namespace glarecam::brdf
