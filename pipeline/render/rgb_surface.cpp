#include "pipeline/render/rgb_surface.h"

#include <cairo.h>
#include <fmt/format.h>

#include <cstddef>

namespace glarecam::pipeline {

Result<CairoSurface> createRgbSurface(int width_px, int height_px) {
  CairoSurface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px));
  if (const cairo_status_t status = cairo_surface_status(surface.get());
      status != CAIRO_STATUS_SUCCESS) {
    return fail(ErrorCode::kInternal, fmt::format("cannot allocate a {}x{} picture: {}", width_px,
                                                  height_px, cairo_status_to_string(status)));
  }
  return surface;
}

RgbImage copyRgb(cairo_surface_t* surface) {
  cairo_surface_flush(surface);
  RgbImage image;
  image.width = cairo_image_surface_get_width(surface);
  image.height = cairo_image_surface_get_height(surface);
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  for (int y = 0; y < image.height; ++y) {
    const auto* in =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    std::uint8_t* out = image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3;
    for (int x = 0; x < image.width; ++x) {
      out[3 * x + 0] = static_cast<std::uint8_t>(in[x] >> 16);
      out[3 * x + 1] = static_cast<std::uint8_t>(in[x] >> 8);
      out[3 * x + 2] = static_cast<std::uint8_t>(in[x]);
    }
  }
  return image;
}

}  // namespace glarecam::pipeline
