#include "pipeline/level_field.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace glarecam::pipeline {

namespace {

// A window no wider than this fraction of the lobe's radius at the level: the lobe's departure
// from a quadratic ln L over the window is then of third order in a quarter of its radius.
constexpr double kMaxWindowOfRadius = 0.25;

bool measuredPixel(const calibration::MergedImage& m, std::size_t i) {
  const float value = m.luminance_cd_m2.data()[i];
  const float relative = m.relative_uncertainty.data()[i];
  return m.bound.data()[i] == static_cast<std::uint8_t>(calibration::PixelBound::kMeasured) &&
         std::isfinite(value) && value > 0 && std::isfinite(relative);
}

}  // namespace

SavitzkyGolayWindow savitzkyGolayWindow(int radius) {
  SavitzkyGolayWindow window;
  window.radius = std::max(0, radius);
  if (window.radius == 0) return window;
  // Normal equations of a + d x² + f y² over the window (x, y, xy are odd: they drop out of
  // the value at the centre); the centre's weights are the first row of their inverse.
  double s0 = 0, s2 = 0, s4 = 0;
  for (int i = -window.radius; i <= window.radius; ++i) {
    s0 += 1;
    s2 += i * i;
    s4 += static_cast<double>(i) * i * i * i;
  }
  Eigen::Matrix3d normal;
  normal << s0 * s0, s0 * s2, s0 * s2,  //
      s0 * s2, s0 * s4, s2 * s2,        //
      s0 * s2, s2 * s2, s0 * s4;
  const Eigen::Matrix3d inverse = normal.inverse();
  window.u = inverse(0, 0);
  window.v = inverse(0, 1);
  double sum_squares = 0;
  for (int j = -window.radius; j <= window.radius; ++j)
    for (int i = -window.radius; i <= window.radius; ++i)
      sum_squares += std::pow(window.weight(i, j), 2);
  window.noise_gain = std::sqrt(sum_squares);
  return window;
}

double noiseToStep(double peak_cd_m2, double level, std::size_t region_pixels,
                   double relative_uncertainty) {
  if (!(peak_cd_m2 > level) || !(level > 0) || region_pixels == 0 ||
      !std::isfinite(relative_uncertainty))
    return 0;
  const double radius_px = std::sqrt(static_cast<double>(region_pixels) / std::numbers::pi);
  const double step = 2 * std::log(peak_cd_m2 / level) / radius_px;
  return step > 0 ? relative_uncertainty / step : 0;
}

SavitzkyGolayWindow windowFor(double noise_to_step, std::size_t region_pixels) {
  if (!(noise_to_step > kMaxNoiseToStep)) return savitzkyGolayWindow(0);
  const double radius_px = std::sqrt(static_cast<double>(region_pixels) / std::numbers::pi);
  const int widest =
      std::min(kMaxSmoothingRadius, static_cast<int>(std::floor(kMaxWindowOfRadius * radius_px)));
  SavitzkyGolayWindow window = savitzkyGolayWindow(0);
  for (int r = 1; r <= widest; ++r) {
    window = savitzkyGolayWindow(r);
    if (window.noise_gain * noise_to_step <= kMaxNoiseToStep) break;
  }
  return window;
}

LevelField::LevelField(const calibration::MergedImage& merged) : merged_(&merged) {}

LevelField::LevelField(const calibration::MergedImage& merged, const SavitzkyGolayWindow& window,
                       PixelBox box)
    : merged_(&merged), window_(window) {
  const FloatImage& image = merged.luminance_cd_m2;
  const int width = image.width(), height = image.height(), r = window.radius;
  box_ = {std::max(0, box.x0), std::max(0, box.y0), std::min(width, box.x1),
          std::min(height, box.y1)};
  if (r == 0 || box_.width() <= 0 || box_.height() <= 0) {
    window_ = savitzkyGolayWindow(0);
    return;
  }
  // ln L + u²/2 and the count of unmeasured pixels, over the box grown by the window.
  const PixelBox grown{std::max(0, box_.x0 - r), std::max(0, box_.y0 - r),
                       std::min(width, box_.x1 + r), std::min(height, box_.y1 + r)};
  const int gw = grown.width(), gh = grown.height();
  std::vector<double> g(static_cast<std::size_t>(gw) * gh, 0.0);
  std::vector<int> bad_integral(static_cast<std::size_t>(gw + 1) * (gh + 1), 0);
  for (int y = 0; y < gh; ++y) {
    int row_bad = 0;
    for (int x = 0; x < gw; ++x) {
      const std::size_t i = static_cast<std::size_t>(grown.y0 + y) * width + grown.x0 + x;
      const bool ok = measuredPixel(merged, i);
      if (ok) {
        const double u = merged.relative_uncertainty.data()[i];
        g[static_cast<std::size_t>(y) * gw + x] =
            std::log(static_cast<double>(image.data()[i])) + u * u / 2;
      }
      row_bad += ok ? 0 : 1;
      bad_integral[static_cast<std::size_t>(y + 1) * (gw + 1) + x + 1] =
          bad_integral[static_cast<std::size_t>(y) * (gw + 1) + x + 1] + row_bad;
    }
  }
  // Separable sums: along rows sum g and sum i² g, then along columns.
  std::vector<double> h0(static_cast<std::size_t>(gw) * gh, 0.0), h2(h0.size(), 0.0);
  for (int y = 0; y < gh; ++y) {
    for (int x = r; x + r < gw; ++x) {
      double a = 0, b = 0;
      for (int i = -r; i <= r; ++i) {
        const double v = g[static_cast<std::size_t>(y) * gw + x + i];
        a += v;
        b += i * i * v;
      }
      h0[static_cast<std::size_t>(y) * gw + x] = a;
      h2[static_cast<std::size_t>(y) * gw + x] = b;
    }
  }
  smoothed_ = image;
  mask_.assign(static_cast<std::size_t>(box_.width()) * box_.height(), 0);
  for (int y = box_.y0; y < box_.y1; ++y) {
    for (int x = box_.x0; x < box_.x1; ++x) {
      const int lx = x - grown.x0, ly = y - grown.y0;
      if (lx - r < 0 || ly - r < 0 || lx + r >= gw || ly + r >= gh) continue;  // at the edge
      const auto at = [&](int xx, int yy) {
        return bad_integral[static_cast<std::size_t>(yy) * (gw + 1) + xx];
      };
      const int bad = at(lx + r + 1, ly + r + 1) - at(lx - r, ly + r + 1) - at(lx + r + 1, ly - r) +
                      at(lx - r, ly - r);
      if (bad != 0) continue;
      double s0 = 0, sx = 0, sy = 0;
      for (int j = -r; j <= r; ++j) {
        const std::size_t k = static_cast<std::size_t>(ly + j) * gw + lx;
        s0 += h0[k];
        sx += h2[k];
        sy += j * j * h0[k];
      }
      const double ln_value = window.u * s0 + window.v * (sx + sy);
      smoothed_.at(x, y) = static_cast<float>(std::exp(ln_value));
      mask_[static_cast<std::size_t>(y - box_.y0) * box_.width() + (x - box_.x0)] = 1;
    }
  }
}

bool LevelField::isSmoothed(std::size_t pixel) const {
  if (window_.radius == 0) return false;
  const int width = merged_->luminance_cd_m2.width();
  const int x = static_cast<int>(pixel % static_cast<std::size_t>(width));
  const int y = static_cast<int>(pixel / static_cast<std::size_t>(width));
  if (!box_.contains(x, y)) return false;
  return mask_[static_cast<std::size_t>(y - box_.y0) * box_.width() + (x - box_.x0)] != 0;
}

std::vector<LevelField::Term> LevelField::pullBack(const std::vector<Term>& per_field) const {
  const int width = merged_->luminance_cd_m2.width(), height = merged_->luminance_cd_m2.height();
  const int r = window_.radius;
  // Dense sums over the smoothed box grown by the window, the rest (pixels the field took as
  // they are, outside it) as they come.
  const PixelBox grown{std::max(0, box_.x0 - r), std::max(0, box_.y0 - r),
                       std::min(width, box_.x1 + r), std::min(height, box_.y1 + r)};
  std::vector<std::array<double, 3>> dense;
  if (r > 0) dense.assign(static_cast<std::size_t>(grown.width()) * grown.height(), {0, 0, 0});
  std::vector<Term> sparse;
  const auto add = [&](std::size_t q, const std::array<double, 3>& d, double factor) {
    const int x = static_cast<int>(q % static_cast<std::size_t>(width));
    const int y = static_cast<int>(q / static_cast<std::size_t>(width));
    if (r > 0 && grown.contains(x, y)) {
      auto& cell = dense[static_cast<std::size_t>(y - grown.y0) * grown.width() + (x - grown.x0)];
      for (std::size_t k = 0; k < d.size(); ++k) cell[k] += d[k] * factor;
    } else {
      sparse.push_back({q, {d[0] * factor, d[1] * factor, d[2] * factor}});
    }
  };
  for (const Term& term : per_field) {
    if (!isSmoothed(term.pixel)) {
      add(term.pixel, term.sensitivity, 1.0);
      continue;
    }
    // d field_p / d L_q = field_p w(q - p) / L_q: the window's weights act on ln L. A smoothed
    // pixel's window lies inside the box, so inside the grown box: straight into the dense sums.
    const int px = static_cast<int>(term.pixel % static_cast<std::size_t>(width));
    const int py = static_cast<int>(term.pixel / static_cast<std::size_t>(width));
    const double field = smoothed_.at(px, py);
    for (int j = -r; j <= r; ++j) {
      const float* luminance = merged_->luminance_cd_m2.row(py + j).data() + px;
      auto* cells = dense.data() + static_cast<std::size_t>(py + j - grown.y0) * grown.width() +
                    (px - grown.x0);
      for (int i = -r; i <= r; ++i) {
        const double factor = field * window_.weight(i, j) / luminance[i];
        for (std::size_t k = 0; k < 3; ++k) cells[i][k] += term.sensitivity[k] * factor;
      }
    }
  }
  std::vector<Term> out;
  for (int y = grown.y0; r > 0 && y < grown.y1; ++y) {
    for (int x = grown.x0; x < grown.x1; ++x) {
      const auto& cell =
          dense[static_cast<std::size_t>(y - grown.y0) * grown.width() + (x - grown.x0)];
      if (cell[0] != 0 || cell[1] != 0 || cell[2] != 0)
        out.push_back({static_cast<std::size_t>(y) * width + x, cell});
    }
  }
  // The rest lie outside the grown box, so they never meet a dense pixel: fold them among
  // themselves.
  std::sort(sparse.begin(), sparse.end(),
            [](const Term& a, const Term& b) { return a.pixel < b.pixel; });
  std::vector<Term> folded;
  for (const Term& t : sparse) {
    if (!folded.empty() && folded.back().pixel == t.pixel) {
      for (std::size_t k = 0; k < t.sensitivity.size(); ++k)
        folded.back().sensitivity[k] += t.sensitivity[k];
    } else {
      folded.push_back(t);
    }
  }
  out.insert(out.end(), folded.begin(), folded.end());
  std::sort(out.begin(), out.end(), [](const Term& a, const Term& b) { return a.pixel < b.pixel; });
  return out;
}

}  // namespace glarecam::pipeline
