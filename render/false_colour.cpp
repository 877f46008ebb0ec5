#include "render/false_colour.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/parallel.h"

namespace glarecam::render {
namespace {

constexpr int kLutSize = 1024;
constexpr std::uint32_t kOpaque = 0xFF000000;      // Cairo's RGB24 ignores the top byte
constexpr std::uint32_t kNotFiniteArgb = kOpaque;  // black

std::uint32_t argb(const std::uint8_t rgb[3]) {
  return kOpaque | (std::uint32_t(rgb[0]) << 16) | (std::uint32_t(rgb[1]) << 8) | rgb[2];
}

}  // namespace

void turboColour(double t, std::uint8_t rgb[3]) {
  // Polynomial fit of the Turbo colour map (A. Mikhailov, Google AI blog, 2019).
  static constexpr double kRed[6] = {0.13572138,   4.61539260,    -42.66032258,
                                     132.13108234, -152.94239396, 59.28637943};
  static constexpr double kGreen[6] = {0.09140261,   2.19418839, 4.84296658,
                                       -14.18503333, 4.27729857, 2.82956604};
  static constexpr double kBlue[6] = {0.10667330,   12.64194608,  -60.58204836,
                                      110.36276771, -89.90310912, 27.34824973};
  t = std::clamp(t, 0.0, 1.0);
  auto channel = [t](const double* c) {
    double value = c[5];
    for (int i = 4; i >= 0; --i) value = value * t + c[i];
    return static_cast<std::uint8_t>(std::clamp(value, 0.0, 1.0) * 255.0 + 0.5);
  };
  rgb[0] = channel(kRed);
  rgb[1] = channel(kGreen);
  rgb[2] = channel(kBlue);
}

double LogScale::position(double value) const {
  return std::clamp((std::log10(std::max(value, 1e-30)) - log_min) / (log_max - log_min), 0.0, 1.0);
}

void paintFalseColour(RgbSurface& surface, const FloatImage& values, const ByteImage& marks,
                      const MarkColours& mark_colours, const LogScale& scale, int zoom) {
  std::array<std::uint32_t, kLutSize> lut;
  for (int i = 0; i < kLutSize; ++i) {
    std::uint8_t rgb[3];
    turboColour(static_cast<double>(i) / (kLutSize - 1), rgb);
    lut[static_cast<std::size_t>(i)] = argb(rgb);
  }
  std::array<std::optional<std::uint32_t>, 256> marked;
  for (std::size_t mark = 0; mark < marked.size(); ++mark)
    if (mark_colours[mark]) marked[mark] = argb(rgbBytes(*mark_colours[mark]).data());
  const RgbSurface::Pixels pixels = surface.pixels();
  parallelRows(values.height(), availableThreads(), [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      std::uint32_t* out = pixels.row(y * zoom);
      auto in = values.row(y);
      auto mark = marks.row(y);
      for (int x = 0; x < values.width(); ++x) {
        const std::optional<std::uint32_t>& fixed = marked[mark[static_cast<std::size_t>(x)]];
        const float v = in[static_cast<std::size_t>(x)];
        const std::uint32_t colour =
            fixed ? *fixed
            : !std::isfinite(v)
                ? kNotFiniteArgb
                : lut[static_cast<std::size_t>(scale.position(v) * (kLutSize - 1) + 0.5)];
        std::fill_n(out + static_cast<std::ptrdiff_t>(x) * zoom, zoom, colour);
      }
      for (int copy = 1; copy < zoom; ++copy)
        std::copy_n(out, static_cast<std::size_t>(values.width() * zoom),
                    pixels.row(y * zoom + copy));
    }
  });
}

}  // namespace glarecam::render
