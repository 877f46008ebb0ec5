// A goniophotometer's measurement of a surface's reflection at one angle of incidence
// (docs/brdf.md): the direction toward the source and the BRDF f_r (sr⁻¹) at sampled outgoing
// directions, as a file holds it (brdf_file.h) or the simulated goniophotometer writes it.
//
// Directions are in the sample's frame (surface/specular_frame.h): z the surface normal, θ the
// polar angle from it, φ the azimuth; the incident (θ_i, φ_i) points toward the source. The glare
// analysis runs in the angular plane around the specular direction (SpecularFrame).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/angular_plane.h"
#include "core/error.h"
#include "surface/specular_frame.h"

namespace glarecam::brdf {

using surface::SpecularFrame;

enum class BrdfFileFormat { kPabOpto, kZemax };
const char* toString(BrdfFileFormat format);  // "pabopto", "zemax"

struct BrdfSample {
  double theta_deg = 0;  // outgoing polar angle from the normal, [0, 90]
  double phi_deg = 0;    // outgoing azimuth, [0, 360)
  double brdf_sr = 0;    // f_r in sr⁻¹, >= 0
  int line = 0;          // the file's line it was read from (0: not read from a file)
};

struct BrdfMeasurement {
  std::string file;  // as messages name it
  BrdfFileFormat format = BrdfFileFormat::kPabOpto;
  std::string sample_name;        // the file's, when it gives one
  double incident_theta_deg = 0;  // α, [0, 90)
  double incident_phi_deg = 0;    // toward the source, [0, 360)
  // The relative standard uncertainty of one sample, when the file states it (docs/brdf.md).
  std::optional<double> relative_noise = std::nullopt;
  std::vector<BrdfSample> samples;
};

// Angles of incidence up to this are accepted: at 90° the source grazes the sample.
inline constexpr double kMaxIncidentThetaDeg = 89.0;

// The method's 2-D Gaussian approximation of the lobe (its section 3.3): ln f_r fitted by a
// quadratic in the angular plane over the samples of at least kLobeFitFraction of the peak,
// its principal axes named as the analysis names them (the one nearer the plane of incidence is
// vertical).
struct GaussianLobe {
  double peak_brdf_sr = 0;
  calibration::PlanePointDeg centre;
  double sigma_vertical_deg = 0, sigma_horizontal_deg = 0;
  double orientation_deg = 0;  // of the horizontal axis from the x axis, within ±90°
  std::size_t samples = 0;     // fitted
  // The full axes of its contour at `fraction` of the peak (0 < fraction < 1).
  double verticalAxisDeg(double fraction) const;
  double horizontalAxisDeg(double fraction) const;
};

inline constexpr double kLobeFitFraction = 0.25;
// The grid must put at least this many samples across the lobe's narrower FWHM (the glare spot
// is a few degrees wide: a coarser grid cannot draw its contours).
inline constexpr double kMinSamplesAcrossFwhm = 5.0;
// A peak farther than this from the specular direction (and than two sample spacings) is
// warned about: the file's incident φ is probably the direction away from the source.
inline constexpr double kPeakOffsetWarningDeg = 1.0;

struct SamplingCheck {
  GaussianLobe lobe;
  std::size_t peak_index = 0;         // the largest sample, in measurement.samples
  double peak_offset_deg = 0;         // its angle from the specular direction
  double spacing_deg = 0;             // median nearest-neighbour distance on the lobe
  double coarsest_spacing_deg = 0;    // the largest (where a lab's rings widen)
  double samples_across_fwhm = 0;     // across the narrower FWHM
  std::vector<std::string> warnings;  // the peak off the specular direction
};

// Fits the Gaussian lobe and checks the grid: kBadInput naming the file (and the peak's line)
// when there are too few samples on the lobe to fit it, or fewer than kMinSamplesAcrossFwhm
// across its FWHM.
Result<SamplingCheck> checkSampling(const BrdfMeasurement& measurement);

// The relative noise of one sample estimated from the data (docs/brdf.md): the median absolute
// third difference of ln f_r along runs of four consecutive, evenly spaced samples on the lobe
// (zero for any Gaussian lobe, so only noise and non-Gaussian shape remain), scaled to a
// standard deviation; nullopt with fewer than kMinNoiseRuns runs.
std::optional<double> estimateRelativeNoise(const BrdfMeasurement& measurement);
inline constexpr std::size_t kMinNoiseRuns = 10;

}  // namespace glarecam::brdf
