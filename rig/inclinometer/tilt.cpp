#include "rig/inclinometer/tilt.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/angles.h"

namespace glarecam::rig {

namespace {

using Vector = std::array<double, 3>;

// Below this a horizontal direction is lost in rounding: the edge stands vertical, or the module
// lies flat and its normal has no azimuth (both keep the configured facing).
constexpr double kDegenerateHorizontal = 1e-9;
constexpr double kQuarterTurnDeg = 90.0;

// x in [0, 360), and 359.9999999 printed as 360.00 becomes 0.
double wrap360(double x_deg) {
  double wrapped = std::fmod(x_deg, 360.0);
  if (wrapped < 0) wrapped += 360.0;
  return wrapped >= 360.0 - 1e-9 ? 0.0 : wrapped;
}

// Rotation about x then y by the zero offset: the inverse of the mounting rotation that makes a
// level module read `offset` (sensor gravity = Rx(-ox) Ry(-oy) e_z).
Vector unmount(const Vector& g, const AxisTilt& offset) {
  const double cx = std::cos(radians(offset.x_deg)), sx = std::sin(radians(offset.x_deg));
  const double cy = std::cos(radians(offset.y_deg)), sy = std::sin(radians(offset.y_deg));
  const Vector about_x{g[0], cx * g[1] - sx * g[2], sx * g[1] + cx * g[2]};  // Rx(ox)
  return {cy * about_x[0] + sy * about_x[2], about_x[1], -sy * about_x[0] + cy * about_x[2]};
}

// The mounting rotation itself: Ry(-oy) then Rx(-ox), undoing unmount().
Vector mount(const Vector& g, const AxisTilt& offset) {
  const double cx = std::cos(radians(offset.x_deg)), sx = std::sin(radians(offset.x_deg));
  const double cy = std::cos(radians(offset.y_deg)), sy = std::sin(radians(offset.y_deg));
  const Vector about_y{cy * g[0] - sy * g[2], g[1], sy * g[0] + cy * g[2]};
  return {about_y[0], cx * about_y[1] + sx * about_y[2], -sx * about_y[1] + cx * about_y[2]};
}

AxisTilt tiltOf(const Vector& g) {
  return {degrees(std::atan2(g[1], g[2])), degrees(std::atan2(-g[0], std::hypot(g[1], g[2])))};
}

double magnitudeG(const AccelerationSample& s) {
  return std::sqrt(s.x_g * s.x_g + s.y_g * s.y_g + s.z_g * s.z_g);
}

// Running mean and variance (Welford): numerically safe for the tiny scatter of a still rig.
struct RunningStats {
  int n = 0;
  double mean = 0.0;
  double m2 = 0.0;
  void add(double x) {
    ++n;
    const double delta = x - mean;
    mean += delta / n;
    m2 += delta * (x - mean);
  }
  double stddev() const { return n > 1 ? std::sqrt(m2 / (n - 1)) : 0.0; }
};

}  // namespace

Status TiltOptions::validate() const {
  if (samples < kMinTiltSamples || samples > kMaxTiltSamples)
    return badInput(fmt::format("inclinometer samples {} must be in [{}, {}]", samples,
                                kMinTiltSamples, kMaxTiltSamples));
  if (!(max_tilt_std_deg > 0.0))
    return badInput(
        fmt::format("inclinometer max_tilt_std_deg {} must be positive", max_tilt_std_deg));
  if (!(gravity_tolerance_g > 0.0 && gravity_tolerance_g < 1.0))
    return badInput(
        fmt::format("inclinometer gravity tolerance {} g must be in (0, 1)", gravity_tolerance_g));
  return {};
}

AxisTilt axisTilt(const AccelerationSample& s) { return tiltOf({s.x_g, s.y_g, s.z_g}); }

double moduleTiltDeg(const AxisTilt& tilt) {
  const double c = std::cos(radians(tilt.x_deg)) * std::cos(radians(tilt.y_deg));
  return degrees(std::acos(std::clamp(c, -1.0, 1.0)));
}

AxisTilt correctedTilt(const AccelerationSample& s, const InclinometerZeroOffset& zero) {
  return tiltOf(unmount({s.x_g, s.y_g, s.z_g}, zero.offset));
}

AccelerationSample mountedGravity(const AxisTilt& tilt, const AxisTilt& mounting_offset) {
  const double cx = std::cos(radians(tilt.x_deg)), sx = std::sin(radians(tilt.x_deg));
  const double cy = std::cos(radians(tilt.y_deg)), sy = std::sin(radians(tilt.y_deg));
  const Vector g = mount({-sy, cy * sx, cy * cx}, mounting_offset);
  return {g[0], g[1], g[2], std::nullopt};
}

sun::ModuleOrientation moduleOrientation(const AxisTilt& tilt, double facing_azimuth_deg) {
  const AccelerationSample up_sample = mountedGravity(tilt, {});  // "up", in the sensor's frame
  const Vector up{up_sample.x_g, up_sample.y_g, up_sample.z_g};
  sun::ModuleOrientation module{moduleTiltDeg(tilt), facing_azimuth_deg};
  // The edge (sensor x) made horizontal: x − (x·up) up. It heads 90° anticlockwise of the facing.
  Vector edge{1.0 - up[0] * up[0], -up[0] * up[1], -up[0] * up[2]};
  const double edge_norm = std::sqrt(edge[0] * edge[0] + edge[1] * edge[1] + edge[2] * edge[2]);
  const double horizontal_normal = std::sin(radians(module.tilt_deg));
  if (edge_norm < kDegenerateHorizontal || horizontal_normal < kDegenerateHorizontal) return module;
  for (double& c : edge) c /= edge_norm;
  // up × edge: horizontal, 90° anticlockwise of the edge, i.e. facing away from the module.
  const Vector back{up[1] * edge[2] - up[2] * edge[1], up[2] * edge[0] - up[0] * edge[2],
                    up[0] * edge[1] - up[1] * edge[0]};
  // The normal (sensor z) along the edge and along `back`, turned into the world's azimuths.
  const double edge_azimuth = radians(facing_azimuth_deg - 90.0);
  const double back_azimuth = radians(facing_azimuth_deg - 180.0);
  const double east = edge[2] * std::sin(edge_azimuth) + back[2] * std::sin(back_azimuth);
  const double north = edge[2] * std::cos(edge_azimuth) + back[2] * std::cos(back_azimuth);
  double azimuth_deg = degrees(std::atan2(east, north));
  // A sensor mounted the other way round (y down the slope) puts the normal behind the facing
  // azimuth: the facing azimuth is where the module faces, so the edge heads the other way.
  if (std::abs(std::remainder(azimuth_deg - facing_azimuth_deg, 360.0)) > kQuarterTurnDeg)
    azimuth_deg += 2 * kQuarterTurnDeg;
  module.azimuth_deg = wrap360(azimuth_deg);
  return module;
}

namespace {

double angleBetweenDeg(const Vector& a, const Vector& b) {
  const Vector c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return degrees(std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                            a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
}

// The scatter of the samples' directions about their mean, per direction: the RMS angle over √2
// (two perpendicular directions share it), so that it compares with one axis's noise. Angles to
// the mean vector, unlike axis tilts (atan2), mean the same whatever the sensor's attitude.
double tiltScatterDeg(const std::vector<Vector>& samples, const Vector& mean) {
  double sum_squares = 0.0;
  for (const Vector& sample : samples) {
    const double angle = angleBetweenDeg(sample, mean);
    sum_squares += angle * angle;
  }
  return std::sqrt(sum_squares / (2.0 * double(samples.size() - 1)));
}

}  // namespace

Result<TiltReading> measureTilt(Inclinometer& inclinometer, const TiltOptions& options,
                                const InclinometerZeroOffset& zero,
                                const std::function<void()>& on_sample) {
  GLARECAM_CHECK(options.validate());
  const std::string& uri = inclinometer.info().uri;
  std::vector<Vector> samples;
  samples.reserve(options.samples);
  RunningStats x, y, z, temperature;
  for (int i = 0; i < options.samples; ++i) {
    AccelerationSample sample;
    GLARECAM_ASSIGN(sample, inclinometer.read());
    const double magnitude_g = magnitudeG(sample);
    if (!(std::abs(magnitude_g - 1.0) <= options.gravity_tolerance_g))
      return hardwareError(fmt::format(
          "inclinometer {}: sample {} measures {:.3f} g, not gravity alone (±{} g): the rig is "
          "being moved, or the sensor's range or scale is wrong",
          uri, i + 1, magnitude_g, options.gravity_tolerance_g));
    x.add(sample.x_g);
    y.add(sample.y_g);
    z.add(sample.z_g);
    samples.push_back({sample.x_g, sample.y_g, sample.z_g});
    if (sample.temperature_c) temperature.add(*sample.temperature_c);
    if (on_sample) on_sample();
  }
  const double scatter_deg = tiltScatterDeg(samples, {x.mean, y.mean, z.mean});
  if (scatter_deg > options.max_tilt_std_deg)
    return hardwareError(fmt::format(
        "inclinometer {}: the rig is moving (tilt scatter {:.3f}° over {} samples, more than the "
        "{}° allowed); wait for it to settle",
        uri, scatter_deg, options.samples, options.max_tilt_std_deg));

  TiltReading reading;
  reading.samples = options.samples;
  reading.mean = {x.mean, y.mean, z.mean,
                  temperature.n > 0 ? std::optional(temperature.mean) : std::nullopt};
  reading.raw_tilt = axisTilt(reading.mean);
  reading.tilt = correctedTilt(reading.mean, zero);
  reading.module_tilt_deg = moduleTiltDeg(reading.tilt);
  reading.tilt_std_deg = scatter_deg;
  const double mean_uncertainty_deg = scatter_deg / std::sqrt(double(options.samples));
  reading.tilt_uncertainty_deg = std::hypot(mean_uncertainty_deg, zero.uncertainty_deg);
  return reading;
}

InclinometerZeroOffset flipZeroOffset(const TiltReading& first, const TiltReading& second) {
  // Turned 180° on the surface (about its normal), the up direction's components along the
  // module's x and y change sign and the one along its normal does not: the bisector of the two
  // up directions, in the sensor's axes, is the normal itself, i.e. what a level surface reads.
  // Exact for any surface tilt (the half-sum of axis tilts is only to first order).
  const auto unit = [](const AccelerationSample& g) {
    const double norm = magnitudeG(g);
    return Vector{g.x_g / norm, g.y_g / norm, g.z_g / norm};
  };
  const Vector a = unit(first.mean), b = unit(second.mean);
  InclinometerZeroOffset zero;
  zero.offset = tiltOf({a[0] + b[0], a[1] + b[1], a[2] + b[2]});
  // Each reading's mean has σ/√N per direction; the bisector carries the root-sum-square over two.
  const auto sem = [](const TiltReading& r) {
    return r.tilt_std_deg / std::sqrt(double(r.samples));
  };
  zero.uncertainty_deg = std::hypot(sem(first), sem(second)) / 2.0;
  return zero;
}

}  // namespace glarecam::rig
