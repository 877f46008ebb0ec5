#include "capture/sim/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "calibration/radiometry.h"
#include "core/parallel.h"

namespace glarecam::capture {
namespace {

// Above this mean the Poisson distribution is replaced by its normal approximation
// (relative error of the variance below 1e-3, far under the merge's tolerance).
constexpr double kNormalApproximationElectrons = 1000.0;

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser: independent streams per row
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

RawFrame exposeFrame(const FloatImage& luminance_cd_m2, const FrameSpec& frame,
                     const Calibration& calibration, const SensorModel& sensor, std::uint64_t seed,
                     const SensorDefectMap* defects) {
  const calibration::FrameRadiometry radiometry = calibration::frameRadiometry(frame, calibration);
  const double electrons_per_cd_m2 =
      1.0 / (radiometry.scale_cd_m2_per_dn * radiometry.dn_per_electron);
  const double full_scale = sensor.full_scale_dn();
  RawFrame raw(luminance_cd_m2.width(), luminance_cd_m2.height());
  const std::uint64_t frame_seed =
      mix(seed ^ mix(static_cast<std::uint64_t>(frame.exposure_us * 1000.0)));
  parallelRows(raw.height(), availableThreads(), [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      std::mt19937_64 rng(mix(frame_seed + static_cast<std::uint64_t>(y)));
      std::normal_distribution<double> unit_normal(0.0, 1.0);
      auto in = luminance_cd_m2.row(y);
      auto out = raw.row(y);
      for (std::size_t x = 0; x < in.size(); ++x) {
        const double mean_electrons =
            std::max(0.0, static_cast<double>(in[x]) * electrons_per_cd_m2);
        double electrons;
        if (mean_electrons > kNormalApproximationElectrons) {
          electrons = mean_electrons + std::sqrt(mean_electrons) * unit_normal(rng);
        } else if (mean_electrons > 0.0) {
          electrons =
              static_cast<double>(std::poisson_distribution<long long>(mean_electrons)(rng));
        } else {
          electrons = 0.0;
        }
        double dn = sensor.black_level_dn + electrons * radiometry.dn_per_electron +
                    radiometry.read_noise_dn * unit_normal(rng);
        if (defects) {
          dn += defects->offset_dn.row(y)[x] +
                defects->dark_current_dn_per_us.row(y)[x] * frame.exposure_us;
        }
        out[x] = static_cast<std::uint16_t>(std::clamp(std::round(dn), 0.0, full_scale));
      }
    }
  });
  return raw;
}

SensorDefectMap sensorDefectMap(int width, int height, const SensorDefects& defects,
                                std::uint64_t sensor_seed) {
  SensorDefectMap map{FloatImage(width, height, 0.0f), FloatImage(width, height, 0.0f), {}};
  std::mt19937_64 rng(mix(sensor_seed));
  std::normal_distribution<double> unit_normal(0.0, 1.0);
  // Every pixel draws its offset even without a fixed pattern: the hot pixels then fall where
  // they fall with one, whatever the pattern's size.
  for (std::size_t i = 0; i < map.offset_dn.pixelCount(); ++i)
    map.offset_dn.data()[i] = static_cast<float>(defects.fixed_pattern_dn * unit_normal(rng));
  std::uniform_int_distribution<int> column(0, width - 1), row(0, height - 1);
  std::uniform_real_distribution<double> rate(kHotRateMinDnPerUs, kHotRateMaxDnPerUs);
  std::set<std::pair<int, int>> hot;
  while (static_cast<int>(hot.size()) < std::min(defects.hot_pixels, width * height)) {
    const std::pair<int, int> p{column(rng), row(rng)};
    if (hot.insert(p).second)
      map.dark_current_dn_per_us.at(p.first, p.second) = static_cast<float>(rate(rng));
  }
  map.hot_pixels.assign(hot.begin(), hot.end());
  return map;
}

}  // namespace glarecam::capture
