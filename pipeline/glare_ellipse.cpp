#include "pipeline/glare_ellipse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <type_traits>

#include "core/angles.h"
#include "core/neighbourhood.h"
#include "core/parallel.h"
#include "pipeline/iso_contour.h"
#include "pipeline/level_field.h"

namespace glarecam::pipeline {
namespace {

using calibration::AngularPlane;
using calibration::PixelPoint;
using calibration::Ray;

// Fewer observed contour points than this cannot tell an ellipse's five parameters from noise
// and pixelation: a region of about 4 x 4 pixels (16 boundary edges). On the 16 x 16 px images
// the simulator allows, 8 points of a 4-pixel region gave axes 20 % off with tiny uncertainties.
constexpr std::size_t kMinContourPoints = 16;
// Re-centring the angular plane on the fitted centre converges in two or three rounds; stop
// when the centre moves less than this (far below any axis's uncertainty).
constexpr int kMaxRecentring = 6;
constexpr double kRecentredDeg = 1e-7;
// Step along a contour point's pixel segment for the numerical d(plane position)/d(position).
constexpr double kDerivativeStepPx = 1e-3;
// A camera model whose undistortion does not map back onto the pixel within this is not
// invertible there (a distortion polynomial that folds over).
constexpr double kMaxRoundTripPx = 0.01;
constexpr int kSolidAngleSteps = 720;
// The solid angle's derivatives by central differences of this fraction of the semi-minor axis:
// the function is smooth (a sum of cosines), so the error is of its square, ~1e-12.
constexpr double kSolidAngleStepFraction = 1e-6;
// An ellipse whose semi-major axis reaches a quarter turn covers a hemisphere: the angular plane
// (and the method) mean nothing there.
constexpr double kMaxSemiAxisDeg = 90.0;

std::optional<PixelIndex> seedPixel(const FloatImage& image, const LuminancePeak& peak,
                                    double level) {
  const int cx = std::clamp(static_cast<int>(std::lround(peak.x_px)), 0, image.width() - 1);
  const int cy = std::clamp(static_cast<int>(std::lround(peak.y_px)), 0, image.height() - 1);
  std::optional<PixelIndex> best;
  float best_value = 0;
  forEach3x3(image.width(), image.height(), cx, cy, [&](int x, int y) {
    const float v = image.at(x, y);
    if (!std::isfinite(v) || !(v >= level) || (best && v <= best_value)) return;
    best = PixelIndex{x, y};
    best_value = v;
  });
  return best;
}

// The observed contour points (not on the image border), their rays, and the rays of the
// points moved a little along their pixel segments (for derivatives).
struct ContourRays {
  std::vector<const ContourPoint*> points;
  std::vector<PixelPoint> pixels;
  std::vector<Ray> rays, stepped_rays;
};

// The observed contour points and their rays; nothing when the camera model cannot be inverted
// at one of them.
std::optional<ContourRays> contourRays(const RegionContour& contour,
                                       const calibration::CameraModel& camera) {
  ContourRays result;
  std::vector<PixelPoint> stepped;
  for (const ContourPoint& point : contour.points) {
    if (point.on_border) continue;
    result.points.push_back(&point);
    result.pixels.push_back({point.x_px, point.y_px});
    stepped.push_back({point.x_px + kDerivativeStepPx * point.step_x,
                       point.y_px + kDerivativeStepPx * point.step_y});
  }
  result.rays = camera.rays(result.pixels);
  result.stepped_rays = camera.rays(stepped);
  for (std::size_t i = 0; i < result.rays.size(); ++i) {
    const PixelPoint back = camera.project(result.rays[i]);
    const PixelPoint& pixel = result.pixels[i];
    if (!(std::hypot(back.x - pixel.x, back.y - pixel.y) <= kMaxRoundTripPx)) return std::nullopt;
  }
  return result;
}

Point2 toPoint(const calibration::PlanePointDeg& p) { return {p.x_deg, p.y_deg}; }
calibration::PlanePointDeg toPlanePoint(const Point2& p) { return {p.x, p.y}; }

struct PlaneFit {
  AngularPlane plane;
  std::vector<Point2> points;
  EllipseFit fit;
};

std::optional<EllipseFit> fitInPlane(const AngularPlane& plane, const std::vector<Ray>& rays,
                                     std::vector<Point2>& points,
                                     const std::optional<Ellipse>& initial) {
  points.clear();
  for (const Ray& ray : rays) points.push_back(toPoint(plane.toPlane(ray)));
  return fitEllipse(points, initial);
}

// Fit in the plane around the contour's mean direction, then re-centre on the fitted centre
// (the plane is exact only about its own origin) until the centre stays put.
std::optional<PlaneFit> fitRecentred(const ContourRays& contour,
                                     const calibration::CameraModel& camera) {
  PixelPoint mean;
  for (const PixelPoint& p : contour.pixels) mean = {mean.x + p.x, mean.y + p.y};
  const auto n = static_cast<double>(contour.pixels.size());
  PlaneFit result{AngularPlane(camera.ray({mean.x / n, mean.y / n})), {}, {}};
  std::optional<Ellipse> previous;  // re-centred on the origin: the start of the next round
  for (int round = 0;; ++round) {
    auto fit = fitInPlane(result.plane, contour.rays, result.points, previous);
    if (!fit) return std::nullopt;
    result.fit = std::move(*fit);
    const Ray centre = result.plane.toRay(toPlanePoint(result.fit.ellipse.centre));
    const bool settled =
        calibration::angleBetweenDeg(centre, result.plane.centre()) < kRecentredDeg;
    // The plane moves only when another round fits in it: points, fit and plane stay together.
    if (settled || round + 1 == kMaxRecentring) break;
    result.plane = AngularPlane(centre);
    previous = result.fit.ellipse;
    previous->centre = {0, 0};
  }
  return result;
}

double distancePx(const PixelPoint& a, const PixelPoint& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// Axes as angles between the rays through their end points, orientation, and pixel sizes.
void measureAxes(const PlaneFit& fitted, const calibration::CameraModel& camera,
                 GlareEllipse& out) {
  const Ellipse& e = fitted.fit.ellipse;
  const auto end = [&](double t) { return fitted.plane.toRay(toPlanePoint(e.pointAt(t))); };
  const Ray major_a = end(0), major_b = end(std::numbers::pi);
  const Ray minor_a = end(std::numbers::pi / 2), minor_b = end(-std::numbers::pi / 2);
  out.major_deg = calibration::angleBetweenDeg(major_a, major_b);
  out.minor_deg = calibration::angleBetweenDeg(minor_a, minor_b);
  out.orientation_deg = degrees(e.angle_rad);
  const bool major_is_vertical = out.majorIsVertical();
  out.vertical_deg = major_is_vertical ? out.major_deg : out.minor_deg;
  out.horizontal_deg = major_is_vertical ? out.minor_deg : out.major_deg;
  const Ray centre = fitted.plane.toRay(toPlanePoint(e.centre));
  out.centre_px = camera.project(centre);
  out.centre_direction = calibration::directionFromAxis(centre);
  out.semi_major_px = distancePx(camera.project(major_a), camera.project(major_b)) / 2;
  out.semi_minor_px = distancePx(camera.project(minor_a), camera.project(minor_b)) / 2;
  out.solid_angle_sr = ellipseSolidAngleSr(e.semi_major, e.semi_minor);
  out.fit_rms_deg = fitted.fit.rms_residual;
  const double px_per_deg = (out.semi_major_px + out.semi_minor_px) / (e.semi_major + e.semi_minor);
  out.fit_rms_px = out.fit_rms_deg * px_per_deg;
  out.plane_centre = fitted.plane.centre();
  out.plane_ellipse = e;
}

// Linear propagation of the pixels' and the level's noise into the semi-axes, the orientation and
// the solid angle (see header), through the field the contour was traced in (level_field.h), and
// the residual the contour's noise alone would leave, to judge the shape by the rest.
void propagateUncertainty(const PlaneFit& fitted, const ContourRays& contour,
                          const calibration::MergedImage& merged, const LevelField& field,
                          double level_sigma_cd_m2, GlareEllipse& out) {
  const auto sigma = [&](std::size_t pixel) {
    return static_cast<double>(merged.relative_uncertainty.data()[pixel]) *
           merged.luminance_cd_m2.data()[pixel];
  };
  // A field pixel's noise: the merged pixel's, or the window's share of it where smoothed.
  const auto field_sigma = [&](std::size_t pixel) {
    if (!field.isSmoothed(pixel)) return sigma(pixel);
    return field.noiseGain() * static_cast<double>(merged.relative_uncertainty.data()[pixel]) *
           field.values().data()[pixel];
  };
  std::vector<LevelField::Term> per_field;  // d(a, b, angle) / d(field value)
  double level_a = 0, level_b = 0, level_angle = 0, expected_variance = 0;
  for (std::size_t i = 0; i < contour.points.size(); ++i) {
    const ContourPoint& point = *contour.points[i];
    const Point2 stepped = toPoint(fitted.plane.toPlane(contour.stepped_rays[i]));
    const Point2 dq{(stepped.x - fitted.points[i].x) / kDerivativeStepPx,
                    (stepped.y - fitted.points[i].y) / kDerivativeStepPx};
    const auto& s = fitted.fit.axis_sensitivity[i];
    const double ga = s[0] * dq.x + s[1] * dq.y, gb = s[2] * dq.x + s[3] * dq.y;
    const auto& r = fitted.fit.angle_sensitivity[i];
    const double gangle = r[0] * dq.x + r[1] * dq.y;
    double t_variance = 0;
    for (std::size_t k = 0; k < point.pixels.size(); ++k) {
      if (point.dt_dvalue[k] == 0) continue;
      const double t = point.dt_dvalue[k];
      per_field.push_back({point.pixels[k], {ga * t, gb * t, gangle * t}});
      // The slots' noises are taken as independent (they are not quite, where smoothed): this
      // is only the shape residual's noise floor.
      t_variance += std::pow(t * field_sigma(point.pixels[k]), 2);
    }
    level_a += ga * point.dt_dlevel;
    level_b += gb * point.dt_dlevel;
    level_angle += gangle * point.dt_dlevel;
    const double along_normal = fitted.fit.normals[i].x * dq.x + fitted.fit.normals[i].y * dq.y;
    if (std::isfinite(t_variance)) {
      expected_variance += along_normal * along_normal * t_variance;
    } else {
      ++out.unweighted_contour_points;
    }
  }
  std::sort(per_field.begin(), per_field.end(),
            [](const auto& a, const auto& b) { return a.pixel < b.pixel; });
  const std::vector<LevelField::Term> per_pixel = field.pullBack(per_field);
  // The solid angle moves with both semi-axes at once: its own sum, not the axes' variances.
  const Ellipse& e = fitted.fit.ellipse;
  const double step = kSolidAngleStepFraction * e.semi_minor;
  const double domega_da = (ellipseSolidAngleSr(e.semi_major + step, e.semi_minor) -
                            ellipseSolidAngleSr(e.semi_major - step, e.semi_minor)) /
                           (2 * step);
  const double domega_db = (ellipseSolidAngleSr(e.semi_major, e.semi_minor + step) -
                            ellipseSolidAngleSr(e.semi_major, e.semi_minor - step)) /
                           (2 * step);
  double var_a = std::pow(level_a * level_sigma_cd_m2, 2);
  double var_b = std::pow(level_b * level_sigma_cd_m2, 2);
  double var_angle = std::pow(level_angle * level_sigma_cd_m2, 2);
  double var_omega = std::pow((domega_da * level_a + domega_db * level_b) * level_sigma_cd_m2, 2);
  for (const LevelField::Term& term : per_pixel) {
    const double s = sigma(term.pixel);
    if (!std::isfinite(s)) continue;
    const auto& [sa, sb, sangle] = term.sensitivity;
    var_a += s * s * sa * sa;
    var_b += s * s * sb * sb;
    var_angle += s * s * sangle * sangle;
    var_omega += s * s * std::pow(domega_da * sa + domega_db * sb, 2);
  }
  const bool major_is_vertical = out.majorIsVertical();
  const double major_sigma = 2 * std::sqrt(var_a), minor_sigma = 2 * std::sqrt(var_b);
  out.vertical_uncertainty_deg = major_is_vertical ? major_sigma : minor_sigma;
  out.horizontal_uncertainty_deg = major_is_vertical ? minor_sigma : major_sigma;
  out.orientation_uncertainty_deg = degrees(std::sqrt(var_angle));
  out.solid_angle_uncertainty_sr = std::sqrt(var_omega);
  const double rms = fitted.fit.rms_residual;
  const double noise_ms = expected_variance / static_cast<double>(contour.points.size());
  out.shape_residual_fraction =
      std::sqrt(std::max(0.0, rms * rms - noise_ms)) / fitted.fit.ellipse.semi_minor;
}

// The merged pixels' typical relative uncertainty on the inside of a contour (NaN when none has
// one).
double contourRelativeUncertainty(const RegionContour& contour,
                                  const calibration::MergedImage& merged) {
  std::vector<double> values;
  for (const ContourPoint& p : contour.points) {
    if (p.on_border) continue;
    const double u = merged.relative_uncertainty.data()[p.pixels[1]];  // the inside pixel
    if (std::isfinite(u)) values.push_back(u);
  }
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The contour's pixel box grown by `margin`.
PixelBox contourBox(const RegionContour& contour, int margin) {
  PixelBox box{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(),
               std::numeric_limits<int>::min(), std::numeric_limits<int>::min()};
  for (const ContourPoint& p : contour.points) {
    box.x0 = std::min(box.x0, static_cast<int>(std::floor(p.x_px)));
    box.y0 = std::min(box.y0, static_cast<int>(std::floor(p.y_px)));
    box.x1 = std::max(box.x1, static_cast<int>(std::ceil(p.x_px)) + 1);
    box.y1 = std::max(box.y1, static_cast<int>(std::ceil(p.y_px)) + 1);
  }
  return {box.x0 - margin, box.y0 - margin, box.x1 + margin, box.y1 + margin};
}

// The part `box` (clipped to the image) of a merged image.
calibration::MergedImage cropMerged(const calibration::MergedImage& merged, const PixelBox& box) {
  const auto crop = [&](const auto& image) {
    using Pixel = std::remove_cvref_t<decltype(*image.data())>;
    Image<Pixel> out = Image<Pixel>::uninitialized(box.width(), box.height());
    for (int y = 0; y < box.height(); ++y) {
      const auto row = image.row(box.y0 + y);
      std::copy_n(row.begin() + box.x0, box.width(), out.row(y).begin());
    }
    return out;
  };
  return {crop(merged.luminance_cd_m2), crop(merged.relative_uncertainty),
          crop(merged.valid_frames), crop(merged.bound)};
}

// Crops smaller than this fraction of the image are worth their copy.
constexpr double kMaxCropFraction = 0.5;

}  // namespace

const char* toString(EllipseStatus status) {
  switch (status) {
    case EllipseStatus::kMeasured:
      return "measured";
    case EllipseStatus::kBelowLevel:
      return "below_level";
    case EllipseStatus::kPeakIsBound:
      return "peak_is_bound";
    case EllipseStatus::kNoPixelAtLevel:
      return "no_pixel_at_level";
    case EllipseStatus::kTooSmall:
      return "too_small";
    case EllipseStatus::kFillsImage:
      return "fills_image";
    case EllipseStatus::kCameraModelNotInvertible:
      return "camera_model_not_invertible";
    case EllipseStatus::kNotAnEllipse:
      return "not_an_ellipse";
  }
  return "unknown";
}

std::optional<EllipseStatus> ellipseStatusFromString(std::string_view text) {
  for (EllipseStatus status :
       {EllipseStatus::kMeasured, EllipseStatus::kBelowLevel, EllipseStatus::kPeakIsBound,
        EllipseStatus::kNoPixelAtLevel, EllipseStatus::kTooSmall, EllipseStatus::kFillsImage,
        EllipseStatus::kCameraModelNotInvertible, EllipseStatus::kNotAnEllipse}) {
    if (text == toString(status)) return status;
  }
  return std::nullopt;
}

std::vector<EllipseMeasurement> measureGlareEllipses(const calibration::MergedImage& merged,
                                                     const calibration::CameraModel& camera,
                                                     const LuminancePeak& peak,
                                                     const std::vector<EllipseLevel>& levels) {
  const FloatImage& image = merged.luminance_cd_m2;
  // The levels on all threads, the lowest (the largest contours, the longest tasks) first.
  std::vector<std::size_t> order(levels.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return levels[a].level_cd_m2 < levels[b].level_cd_m2;
  });
  const auto measureAll = [&](const calibration::MergedImage& on,
                              const calibration::CameraModel& on_camera,
                              const LuminancePeak& on_peak, int dx, int dy) {
    std::vector<EllipseMeasurement> out(levels.size());
    parallelTasks(static_cast<int>(levels.size()), availableThreads(), [&](int task) {
      const std::size_t i = order[static_cast<std::size_t>(task)];
      out[i] = measureGlareEllipse(on, on_camera, on_peak, levels[i].level_cd_m2,
                                   levels[i].relative_uncertainty);
      if (!out[i].ellipse || (dx == 0 && dy == 0)) return;
      GlareEllipse& e = *out[i].ellipse;
      e.centre_px = {e.centre_px.x + dx, e.centre_px.y + dy};
      for (PixelPoint& p : e.contour_px) p = {p.x + dx, p.y + dy};
    });
    return out;
  };
  // The lowest level that floods anything: levels above the maximum end before any flood.
  double lowest = std::numeric_limits<double>::infinity();
  for (const EllipseLevel& level : levels) {
    if (std::isfinite(level.level_cd_m2) && level.level_cd_m2 > 0 &&
        level.level_cd_m2 <= peak.value_cd_m2)
      lowest = std::min(lowest, level.level_cd_m2);
  }
  if (image.empty() || levels.size() < 2 || !std::isfinite(lowest))
    return measureAll(merged, camera, peak, 0, 0);
  const int px = std::clamp(static_cast<int>(std::lround(peak.x_px)), 0, image.width() - 1);
  const int py = std::clamp(static_cast<int>(std::lround(peak.y_px)), 0, image.height() - 1);
  PixelBox box{px, py, px + 1, py + 1};
  for (const RegionExtent& r : findRegions(image, lowest, kMinRegionPixels))
    box = {std::min(box.x0, r.x0), std::min(box.y0, r.y0), std::max(box.x1, r.x1 + 1),
           std::max(box.y1, r.y1 + 1)};
  box = {std::max(0, box.x0 - kLevelCropMarginPx), std::max(0, box.y0 - kLevelCropMarginPx),
         std::min(image.width(), box.x1 + kLevelCropMarginPx),
         std::min(image.height(), box.y1 + kLevelCropMarginPx)};
  const double fraction = static_cast<double>(box.width()) * box.height() /
                          (static_cast<double>(image.width()) * image.height());
  if (fraction > kMaxCropFraction) return measureAll(merged, camera, peak, 0, 0);
  Intrinsics shifted = camera.intrinsics();
  shifted.cx -= box.x0;
  shifted.cy -= box.y0;
  LuminancePeak shifted_peak = peak;
  shifted_peak.x_px -= box.x0;
  shifted_peak.y_px -= box.y0;
  return measureAll(cropMerged(merged, box), calibration::CameraModel(shifted), shifted_peak,
                    box.x0, box.y0);
}

double ellipseSolidAngleSr(double semi_major_deg, double semi_minor_deg) {
  // Omega = integral over psi of (1 - cos R(psi)), R the ellipse's radius in direction psi: the
  // plane's radius is the angle from its centre. Periodic trapezoid rule: spectrally accurate.
  // cos² and sin² of the steps' directions once (every ellipse, five times each, takes them).
  static const auto kSquares = [] {
    std::array<std::array<double, 2>, kSolidAngleSteps> squares{};
    for (int i = 0; i < kSolidAngleSteps; ++i) {
      const double psi = 2 * std::numbers::pi * i / kSolidAngleSteps;
      squares[static_cast<std::size_t>(i)] = {std::pow(std::cos(psi), 2),
                                              std::pow(std::sin(psi), 2)};
    }
    return squares;
  }();
  const double a = radians(semi_major_deg), b = radians(semi_minor_deg);
  double sum = 0;
  for (const auto& [cos2, sin2] : kSquares) {
    const double radius = a * b / std::sqrt(b * b * cos2 + a * a * sin2);
    sum += 1 - std::cos(radius);
  }
  return sum * 2 * std::numbers::pi / kSolidAngleSteps;
}

EllipseMeasurement measureGlareEllipse(const calibration::MergedImage& merged,
                                       const calibration::CameraModel& camera,
                                       const LuminancePeak& peak, double level_cd_m2,
                                       double level_relative_uncertainty) {
  const auto outcome = [&](EllipseStatus status) {
    return EllipseMeasurement{level_cd_m2, status, std::nullopt};
  };
  const FloatImage& image = merged.luminance_cd_m2;
  if (image.empty() || !(level_cd_m2 > 0)) return outcome(EllipseStatus::kBelowLevel);
  const bool reaches = peak.value_cd_m2 >= level_cd_m2;
  // A dark maximum (at most its value) decides only the levels above it, a clipped one (at
  // least its value) only the levels below it.
  if ((peak.method == PeakMethod::kUpperBound && reaches) ||
      (peak.method == PeakMethod::kLowerBound && !reaches))
    return outcome(EllipseStatus::kPeakIsBound);
  if (!reaches) return outcome(EllipseStatus::kBelowLevel);
  const auto seed = seedPixel(image, peak, level_cd_m2);
  ByteImage region_mask;  // the traced region's pixels: counting the others floods it no more
  auto contour = seed ? traceRegionContour(image, level_cd_m2, *seed, &region_mask) : std::nullopt;
  if (!contour) return outcome(EllipseStatus::kNoPixelAtLevel);
  if (contour->touches_all_borders) return outcome(EllipseStatus::kFillsImage);
  // Where the noise is large against the step between pixels, the contour is traced again in a
  // smoothed field (level_field.h); the merged image's own contour only tells where.
  LevelField field(merged);
  const SavitzkyGolayWindow window =
      windowFor(noiseToStep(peak.value_cd_m2, level_cd_m2, contour->region_pixels,
                            contourRelativeUncertainty(*contour, merged)),
                contour->region_pixels);
  if (window.radius > 0) {
    // Room for the smoothed contour to sit a few pixels off the noisy one, and for the cubic's
    // outer pixels.
    const int margin = 2 * window.radius + 4;
    LevelField smoothed(merged, window, contourBox(*contour, margin));
    const auto smoothed_seed = seedPixel(smoothed.values(), peak, level_cd_m2);
    auto retraced = smoothed_seed
                        ? traceRegionContour(smoothed.values(), level_cd_m2, *smoothed_seed)
                        : std::nullopt;
    const PixelBox inner = contourBox(*contour, margin - 2);
    const bool inside =
        retraced &&
        std::all_of(retraced->points.begin(), retraced->points.end(), [&](const ContourPoint& p) {
          return inner.contains(static_cast<int>(std::lround(p.x_px)),
                                static_cast<int>(std::lround(p.y_px)));
        });
    if (inside && !retraced->touches_all_borders) {
      contour = std::move(retraced);
      field = std::move(smoothed);
    }
  }
  const std::size_t observed = static_cast<std::size_t>(std::count_if(
      contour->points.begin(), contour->points.end(), [](const auto& p) { return !p.on_border; }));
  if (observed < kMinContourPoints) return outcome(EllipseStatus::kTooSmall);
  const auto rays = contourRays(*contour, camera);
  if (!rays) return outcome(EllipseStatus::kCameraModelNotInvertible);
  const auto fitted = fitRecentred(*rays, camera);
  if (!fitted || !(fitted->fit.ellipse.semi_major < kMaxSemiAxisDeg))
    return outcome(EllipseStatus::kNotAnEllipse);

  GlareEllipse ellipse;
  ellipse.level_cd_m2 = level_cd_m2;
  measureAxes(*fitted, camera, ellipse);
  const double level_sigma_cd_m2 =
      std::isfinite(level_relative_uncertainty) ? level_relative_uncertainty * level_cd_m2 : 0.0;
  propagateUncertainty(*fitted, *rays, merged, field, level_sigma_cd_m2, ellipse);
  ellipse.smoothing_radius_px = field.radius();
  const double numbers[] = {ellipse.major_deg,
                            ellipse.minor_deg,
                            ellipse.orientation_deg,
                            ellipse.centre_px.x,
                            ellipse.centre_px.y,
                            ellipse.semi_major_px,
                            ellipse.semi_minor_px,
                            ellipse.solid_angle_sr,
                            ellipse.fit_rms_px,
                            ellipse.shape_residual_fraction,
                            ellipse.vertical_uncertainty_deg,
                            ellipse.horizontal_uncertainty_deg,
                            ellipse.solid_angle_uncertainty_sr};
  if (!std::all_of(std::begin(numbers), std::end(numbers),
                   [](double v) { return std::isfinite(v); }))
    return outcome(EllipseStatus::kNotAnEllipse);  // result.json promises numbers
  ellipse.ellipticity_ok = ellipse.shape_residual_fraction <= kMaxEllipticalResidualFraction;
  ellipse.truncated = contour->touches_border;
  // The measured region, even when it is smaller than the noise-speck size, and the others.
  ellipse.regions =
      1 + static_cast<int>(findRegions(image, level_cd_m2, kMinRegionPixels, &region_mask).size());
  ellipse.contour_points = observed;
  ellipse.region_pixels = contour->region_pixels;
  for (const ContourPoint& p : contour->points) ellipse.contour_px.push_back({p.x_px, p.y_px});
  EllipseMeasurement measurement = outcome(EllipseStatus::kMeasured);
  measurement.ellipse = std::move(ellipse);
  return measurement;
}

}  // namespace glarecam::pipeline
