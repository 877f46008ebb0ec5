// The glare ellipse at one luminance level (docs/method.md, "The glare ellipse"): the
// sub-pixel iso-contour (iso_contour.h) of the region holding the luminance maximum, its points
// turned into viewing rays through the camera model, an ellipse fitted (ellipse_fit.h) in the
// angular plane around the region's centre direction (calibration/angular_plane.h, re-centred
// on the fitted centre until it stays put), and each full axis measured as the angle between
// the rays through its two end points. So neither lens distortion nor an off-centre spot biases
// the axes.
//
// Directions are the camera's, not the distorted pixel grid's: horizontal is the camera's x axis
// (the undistorted image horizontal) made perpendicular to the ellipse's centre ray, vertical is
// perpendicular to both (toward image +y). The vertical axis is the ellipse axis closer to that
// vertical (at exactly 45° the major one); orientation is the major axis's angle from that
// horizontal toward +y, in (-90°, 90°], like OpenCV's RotatedRect. On the optical axis these
// are the image's own directions; off-axis they differ from the local pixel grid by the
// perspective shear and the distortion (a few degrees at 25° off-axis), which is the point:
// vertical means the camera's vertical plane (the plane of incidence on a level rig).
//
// Uncertainty: each contour point depends on up to four pixels and on the level (iso_contour.h);
// the fit says how each point moves the semi-axes (ellipse_fit.h). Summing per pixel, then over
// pixels with their merged standard uncertainty (hdr_merge.h), and adding the level's own
// uncertainty (FWHM: the peak's), gives the axes' standard uncertainties by linear propagation.
// Pure function of the merged image, the camera model and the peak; no I/O.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "calibration/angular_plane.h"
#include "calibration/camera_model.h"
#include "calibration/hdr_merge.h"
#include "pipeline/ellipse_fit.h"
#include "pipeline/luminance_peak.h"

namespace glarecam::pipeline {

// Regions smaller than this are not counted as separate glare regions: a hot pixel or a noise
// speck just above the level (a real glare spot covers far more pixels at any usable scale).
inline constexpr std::size_t kMinRegionPixels = 9;
// The fit's shape residual (noise removed) above this fraction of the semi-minor axis flags a
// region as not elliptical: a square region gives about 11 %, a noisy true ellipse well under 1 %.
inline constexpr double kMaxEllipticalResidualFraction = 0.05;

struct GlareEllipse {
  double level_cd_m2 = 0;
  double vertical_deg = 0, horizontal_deg = 0;  // full axes
  double major_deg = 0, minor_deg = 0;
  double orientation_deg = 0;
  calibration::PixelPoint centre_px;
  calibration::DirectionDeg centre_direction;
  double semi_major_px = 0, semi_minor_px = 0;
  double solid_angle_sr = 0;
  double fit_rms_deg = 0, fit_rms_px = 0;
  double shape_residual_fraction = 0;  // noise-corrected fit RMS / semi-minor axis
  bool ellipticity_ok = false;
  bool truncated = false;  // the region touches the image border: fitted on its visible part
  int regions = 0;         // separate regions at or above the level (kMinRegionPixels or more)
  std::size_t contour_points = 0, region_pixels = 0;
  double vertical_uncertainty_deg = 0, horizontal_uncertainty_deg = 0;
  // The major axis's orientation and the solid angle, by the same propagation. The orientation's
  // is meaningful only while it is well below 90° (a nearly round ellipse has none to speak of).
  double orientation_uncertainty_deg = 0, solid_angle_uncertainty_sr = 0;
  std::size_t unweighted_contour_points = 0;  // points next to bound pixels (no noise figure)
  // The Savitzky-Golay window the contour was traced through (level_field.h): its radius in
  // pixels, 0 for the merged luminance itself.
  int smoothing_radius_px = 0;
  // Geometry for pictures: the contour in pixels, and the fitted ellipse (degrees) in the
  // angular plane around `plane_centre`.
  std::vector<calibration::PixelPoint> contour_px;
  calibration::Ray plane_centre;
  Ellipse plane_ellipse;

  // The vertical axis is the one closer to the camera's vertical; at exactly 45° the major one.
  bool majorIsVertical() const { return orientation_deg >= 45.0 || orientation_deg <= -45.0; }
};

enum class EllipseStatus {
  kMeasured,
  kBelowLevel,                // the maximum does not reach the level
  kPeakIsBound,               // the maximum is only a bound that cannot decide (dark but above the
                              // level, or clipped below it), or half of a bound is no FWHM level
  kNoPixelAtLevel,            // the fitted maximum reaches the level, no pixel beside it does
  kTooSmall,                  // too few observed contour points to fit
  kFillsImage,                // the region reaches all four image borders: larger than the view
  kCameraModelNotInvertible,  // the distortion cannot be undone where the contour lies
  kNotAnEllipse,              // the contour determines no ellipse (or one beyond a hemisphere)
};
const char* toString(EllipseStatus status);
// The status toString() names `text`, or nullopt.
std::optional<EllipseStatus> ellipseStatusFromString(std::string_view text);

struct EllipseMeasurement {
  double level_cd_m2 = 0;
  EllipseStatus status = EllipseStatus::kBelowLevel;
  std::optional<GlareEllipse> ellipse;  // when measured
};

// The ellipse of the region at `level_cd_m2` that holds `peak`. `level_relative_uncertainty`
// is the level's own standard uncertainty relative to it (0 for a fixed threshold; a
// non-finite value counts as 0). Every outcome is a status; nothing here fails.
EllipseMeasurement measureGlareEllipse(const calibration::MergedImage& merged,
                                       const calibration::CameraModel& camera,
                                       const LuminancePeak& peak, double level_cd_m2,
                                       double level_relative_uncertainty = 0);

// One level of several measured on one image, with its own relative standard uncertainty.
struct EllipseLevel {
  double level_cd_m2 = 0;
  double relative_uncertainty = 0;
};

// The ellipses at several levels of one image, each exactly as measureGlareEllipse() gives it
// (the same statuses; the axes equal to rounding), sharing the work between levels: the regions
// at the lowest level reached are found once on the whole image, and every level is measured on
// a copy of the image cut to those regions' box (grown by kLevelCropMarginPx, room for the widest
// smoothing window): a region at a higher level lies inside one at a lower level, so its
// contour, its smoothed field and the count of regions are the same there. The levels are
// measured on availableThreads() threads at once (each with one). Pixel positions in the results
// are the whole image's. In the order asked.
std::vector<EllipseMeasurement> measureGlareEllipses(const calibration::MergedImage& merged,
                                                     const calibration::CameraModel& camera,
                                                     const LuminancePeak& peak,
                                                     const std::vector<EllipseLevel>& levels);

// The margin around the lowest level's regions that measureGlareEllipses() keeps: beyond the
// smoothed field's reach (3 kMaxSmoothingRadius + 4 px around a contour, level_field.h) and the
// cubic crossing's two pixels.
inline constexpr int kLevelCropMarginPx = 64;

// Solid angle (sr) of an ellipse in an angular plane, centred on the plane's origin.
double ellipseSolidAngleSr(double semi_major_deg, double semi_minor_deg);

}  // namespace glarecam::pipeline
