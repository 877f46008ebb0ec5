#include "pipeline/false_colour_picture.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "pipeline/luminance_stats.h"
#include "render/canvas.h"
#include "render/false_colour.h"
#include "render/number_format.h"
#include "render/text.h"

namespace glarecam::pipeline {
namespace {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

constexpr double kMaxDecades = 6.0;      // the scale never spans more than this
constexpr double kLowPercentile = 0.01;  // default bottom of the scale
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kBackground{0.12, 0.12, 0.12};  // below a short image, behind the panel

// Layout of the colour-bar panel, in units of the label font size (em), so that it reads the
// same from thumbnails to 12 MP: the font is 1/40 of the image height within 11..48 px.
constexpr double kFontFractionOfHeight = 1.0 / 40.0;
constexpr double kMinFontPx = 11.0, kMaxFontPx = 48.0;
constexpr double kPanelWidthEm = 9.5;      // bar, ticks and labels such as "100k" and "saturated"
constexpr double kMinCanvasHeightEm = 16;  // room for title, bar and legend on short images
constexpr double kBannerHeightEm = 1.6;    // the warning band across the image's top
constexpr double kBarMarginEm = 4.0;       // above the bar (title, unit) and below (legend)
constexpr double kBarWidthEm = 1.5;
constexpr double kFineTickDecades = 2.0;

LogScale chooseScale(const calibration::MergedImage& merged, const FalseColourOptions& options) {
  const FloatImage& luminance = merged.luminance_cd_m2;
  std::vector<float> sample;
  const std::size_t step = summarySampleStep(luminance.pixelCount());
  float max_value = 0;
  for (std::size_t i = 0; i < luminance.pixelCount(); ++i) {
    const float v = luminance.data()[i];
    if (std::isfinite(v)) max_value = std::max(max_value, v);
  }
  for (std::size_t i = 0; i < luminance.pixelCount(); i += step) {  // no division per pixel
    const float v = luminance.data()[i];
    if (std::isfinite(v) && v > 0) sample.push_back(v);
  }
  double top = options.max_cd_m2.value_or(max_value > 0 ? max_value : 1.0);
  double bottom = top / std::pow(10.0, kMaxDecades);
  if (!sample.empty()) {
    auto nth = sample.begin() +
               static_cast<std::ptrdiff_t>(kLowPercentile * static_cast<double>(sample.size() - 1));
    std::nth_element(sample.begin(), nth, sample.end());
    bottom = std::max(bottom, static_cast<double>(*nth));
  }
  bottom = options.min_cd_m2.value_or(bottom);
  if (!(bottom > 0) || bottom >= top) bottom = top / 10.0;
  return {std::log10(bottom), std::log10(top)};
}

// The luminance, saturated pixels (lower bounds) white, under-exposed ones (upper bounds) black.
void paintLuminance(RgbSurface& surface, const calibration::MergedImage& merged,
                    const LogScale& scale, int zoom) {
  MarkColours bound_colours{};
  bound_colours[static_cast<std::size_t>(calibration::PixelBound::kLowerBound)] = kWhite;
  bound_colours[static_cast<std::size_t>(calibration::PixelBound::kUpperBound)] = kBlack;
  paintFalseColour(surface, merged.luminance_cd_m2, merged.bound, bound_colours, scale, zoom);
}

struct PanelLayout {
  double bar_top, bar_bottom, bar_x, bar_width, font_px;
};

void paintColourBar(Canvas& canvas, const PanelLayout& p, const LogScale& scale,
                    const FalseColourOptions& options, bool has_saturated) {
  const Font font{.size = p.font_px};
  const TextStyle label_style{font, kWhite};
  const int steps = static_cast<int>(p.bar_bottom - p.bar_top);
  for (int i = 0; i < steps; ++i) {
    std::uint8_t rgb[3];
    turboColour(1.0 - static_cast<double>(i) / std::max(1, steps - 1), rgb);
    canvas.setColour({rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0});
    canvas.rectangle({p.bar_x, p.bar_top + i}, p.bar_width, 1.0);
    canvas.fill();
  }
  auto yOf = [&](double value) {
    return p.bar_bottom - scale.position(value) * (p.bar_bottom - p.bar_top);
  };
  canvas.setColour(kWhite);
  canvas.setLineWidth(std::max(1.0, p.font_px / 10));
  // Ticks at each decade; on a scale under kFineTickDecades also at 2 and 5 times each, so
  // that a dim, low-contrast image still has values to read.
  const bool fine = scale.log_max - scale.log_min < kFineTickDecades;
  for (int decade = static_cast<int>(std::floor(scale.log_min));
       decade <= static_cast<int>(std::floor(scale.log_max)); ++decade) {
    for (const double step : {1.0, 2.0, 5.0}) {
      const double value = step * std::pow(10.0, decade);
      if ((step != 1.0 && !fine) || std::log10(value) < scale.log_min ||
          std::log10(value) > scale.log_max)
        continue;
      const double y = yOf(value);
      canvas.moveTo({p.bar_x + p.bar_width, y});
      canvas.lineTo({p.bar_x + p.bar_width + p.font_px * 0.4, y});
      canvas.stroke();
      drawText(canvas,
               {p.bar_x + p.bar_width + p.font_px * 0.6, y + p.font_px * kBaselineBelowMiddleEm},
               formatSiPrefixed(value), label_style);
    }
  }
  drawText(canvas, {p.bar_x, p.bar_top - p.font_px * 0.8}, "cd/m\u00b2", label_style);
  if (!options.title.empty())
    drawText(canvas, {p.bar_x, p.font_px * 1.2}, options.title, label_style);
  const double caption_width = p.font_px * (kPanelWidthEm - 1.5);
  for (std::size_t i = 0; i < options.caption.size(); ++i) {
    const std::string& line = options.caption[i];
    const double scale = std::min(1.0, caption_width / textWidth(canvas, line, font));
    drawText(canvas, {p.bar_x, p.font_px * (1.2 + kLineSpacingEm * static_cast<double>(i + 1))},
             line, {{.size = p.font_px * scale}, kWhite});
  }
  // The limit is marked only where it lies on the scale: pinned to an end it would read as
  // "the maximum is the limit".
  const bool limit_on_scale = options.limit_cd_m2 && *options.limit_cd_m2 > 0 &&
                              std::log10(*options.limit_cd_m2) >= scale.log_min &&
                              std::log10(*options.limit_cd_m2) <= scale.log_max;
  if (limit_on_scale) {
    const double y = yOf(*options.limit_cd_m2);
    canvas.setColour(kLimitColour);
    canvas.moveTo({p.bar_x - p.font_px * 0.3, y});
    canvas.lineTo({p.bar_x + p.bar_width, y});
    canvas.stroke();
    drawText(canvas, {p.bar_x + p.bar_width + p.font_px * 0.6, y - p.font_px * 0.5}, "limit",
             {font, kLimitColour});
  }
  if (!has_saturated) return;
  canvas.setColour(kWhite);
  canvas.rectangle({p.bar_x, p.bar_bottom + p.font_px * 0.8}, p.bar_width, p.font_px);
  canvas.fill();
  drawText(canvas, {p.bar_x + p.bar_width + p.font_px * 0.6, p.bar_bottom + p.font_px * 1.7},
           "saturated", label_style);
}

bool hasSaturated(const calibration::MergedImage& merged) {
  const std::uint8_t* bound = merged.bound.data();
  return std::any_of(bound, bound + merged.bound.pixelCount(), [](std::uint8_t b) {
    return b == static_cast<std::uint8_t>(calibration::PixelBound::kLowerBound);
  });
}

}  // namespace

Result<RgbImage> renderFalseColour(const calibration::MergedImage& merged,
                                   const FalseColourOptions& options) {
  const int frame_width = merged.luminance_cd_m2.width();
  const int frame_height = merged.luminance_cd_m2.height();
  if (frame_width <= 0 || frame_height <= 0) return badInput("false colour: empty image");
  const int zoom = std::clamp(options.min_image_height_px / frame_height, 1, kMaxPictureZoom);
  const int width = frame_width * zoom, height = frame_height * zoom;  // as shown
  // The panel scales with the image so labels stay legible from thumbnails to 12 MP.
  const double font_px = std::clamp(height * kFontFractionOfHeight, kMinFontPx, kMaxFontPx);
  const int panel_width = static_cast<int>(font_px * kPanelWidthEm);
  const double caption_em = kLineSpacingEm * static_cast<double>(options.caption.size());
  const int canvas_height =
      std::max(height, static_cast<int>(font_px * (kMinCanvasHeightEm + caption_em)));
  Result<RgbSurface> surface = RgbSurface::create(width + panel_width, canvas_height);
  if (!surface) return std::unexpected(withContext(surface.error(), "false colour"));
  Result<Canvas> context = Canvas::onSurface(*surface);
  if (!context) return std::unexpected(withContext(context.error(), "false colour"));
  Canvas& canvas = *context;
  const LogScale scale = chooseScale(merged, options);
  paint(canvas, kBackground);
  paintLuminance(*surface, merged, scale, zoom);
  if (options.overlay) {
    const Canvas::Saved saved = canvas.save();
    canvas.rectangle({0, 0}, width, height);
    canvas.clip();
    // Pixel (x, y) covers [x, x + 1] of the frame (zoomed on the canvas); overlays draw in the
    // frame's pixel-centre coordinates, their font and lines sized for the canvas.
    canvas.scale(zoom, zoom);
    canvas.translate(0.5, 0.5);
    options.overlay(canvas, font_px / zoom);
  }
  if (!options.banner.empty()) {
    canvas.setColour(kLimitColour);
    canvas.rectangle({0, 0}, width, font_px * kBannerHeightEm);
    canvas.fill();
    drawText(canvas, {width / 2.0, font_px * (kBannerHeightEm / 2 + kBaselineBelowMiddleEm)},
             options.banner, {{.size = font_px, .bold = true}, kWhite, Align::kCentre});
  }
  const PanelLayout layout{font_px * (kBarMarginEm + caption_em),
                           canvas_height - font_px * kBarMarginEm, width + font_px,
                           font_px * kBarWidthEm, font_px};
  paintColourBar(canvas, layout, scale, options, hasSaturated(merged));
  return surface->copyRgb();
}

}  // namespace glarecam::pipeline
