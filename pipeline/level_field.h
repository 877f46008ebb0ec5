// The field a glare ellipse's contour is traced in (glare_ellipse.h). Where the merged image's
// noise at the level is small against the step in luminance from one pixel to the next, that is
// the merged luminance itself. Where it is not (a lobe many pixels across, a level high on the
// lobe where only the shortest frame measures), the iso-contour stops being a linear function of
// the pixels: pixels flip in and out of the region, the region (8-connected, holes filled) grows
// outward, and both the axes and their propagated uncertainty go wrong (issue 23: at 4 times the
// pixels across a lobe the FWHM axes were biased outward by 60 of their own standard errors, and
// scattered 3 to 7 times more than their reported uncertainty). There the field is ln L smoothed
// by a quadratic Savitzky-Golay window (a least-squares fit of ln L = a + b x + c y + d x² + e xy +
// f y² over (2r+1)² pixels, taken at the centre): ln L of a Gaussian lobe is exactly quadratic,
// so the window removes noise without moving the contour, and a lobe near it in shape moves it
// by the window's third-order terms only. The window is the smallest that brings the noise below
// kMaxNoiseToStep of the step, no wider than a quarter of the lobe's radius.
//
// ln L is taken as ln L + u²/2 (u the pixel's relative uncertainty): the mean of the logarithm
// of a noisy value falls short of the logarithm by u²/2. Pixels whose window is not wholly
// measured (near a bound pixel or the image's edge) keep their merged value. The field's values
// are linear combinations of ln L, so pixel noise still propagates exactly: pullBack() maps a
// quantity's sensitivity to field values onto the merged pixels.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "calibration/hdr_merge.h"
#include "core/image.h"

namespace glarecam::pipeline {

// Noise of ln L against its step from one pixel to the next at the level, below which the
// contour of the merged image is used as it is: the linear propagation held at 0.3 and failed
// (2x) at 0.55 (issue 23's measurements); 0.2 leaves a margin.
inline constexpr double kMaxNoiseToStep = 0.1;
// The widest window: 2 x 16 + 1 pixels (a lobe 120 pixels across at its FWHM and more).
inline constexpr int kMaxSmoothingRadius = 16;

// The window's weights of ln L at offset (i, j): u + v (i² + j²); its noise gain sqrt(sum w²).
struct SavitzkyGolayWindow {
  int radius = 0;
  double u = 1, v = 0;
  double noise_gain = 1;
  double weight(int i, int j) const { return u + v * (i * i + j * j); }
};
SavitzkyGolayWindow savitzkyGolayWindow(int radius);

struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

class LevelField {
 public:
  // The merged luminance as it is.
  explicit LevelField(const calibration::MergedImage& merged);
  // Smoothed with `window` inside `box` (clipped to the image), the merged luminance elsewhere.
  LevelField(const calibration::MergedImage& merged, const SavitzkyGolayWindow& window,
             PixelBox box);

  const FloatImage& values() const {
    return window_.radius > 0 ? smoothed_ : merged_->luminance_cd_m2;
  }
  int radius() const { return window_.radius; }
  double noiseGain() const { return window_.noise_gain; }
  bool isSmoothed(std::size_t pixel) const;

  // d(quantities)/d(merged pixel) from d(quantities)/d(field pixel), both sparse, as (pixel,
  // sensitivities) pairs of three quantities; the result sorted by pixel, one entry per pixel.
  struct Term {
    std::size_t pixel;
    std::array<double, 3> sensitivity;
  };
  std::vector<Term> pullBack(const std::vector<Term>& per_field) const;

 private:
  const calibration::MergedImage* merged_;
  SavitzkyGolayWindow window_;
  PixelBox box_;
  FloatImage smoothed_;             // the whole image, when smoothed
  std::vector<std::uint8_t> mask_;  // per pixel of box_: 1 where smoothed
};

// The noise of ln L against its step between neighbouring pixels at `level` on a lobe whose
// maximum is `peak_cd_m2` and whose region at the level covers `region_pixels`, with
// `relative_uncertainty` the merged pixels' typical one there: a Gaussian lobe's
// |d ln L / d r| = 2 ln(peak / level) / r at the radius r of that area.
double noiseToStep(double peak_cd_m2, double level, std::size_t region_pixels,
                   double relative_uncertainty);

// The window for that noise-to-step ratio and region (radius 0: none needed or possible).
SavitzkyGolayWindow windowFor(double noise_to_step, std::size_t region_pixels);

}  // namespace glarecam::pipeline
