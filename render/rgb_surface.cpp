#include "render/rgb_surface.h"

#include <cairo.h>
#include <fmt/format.h>

#include <cstddef>

namespace glarecam::render {

Result<RgbSurface> RgbSurface::create(int width_px, int height_px) {
  CairoSurface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px));
  if (const cairo_status_t status = cairo_surface_status(surface.get());
      status != CAIRO_STATUS_SUCCESS) {
    return fail(ErrorCode::kInternal, fmt::format("cannot allocate a {}x{} picture: {}", width_px,
                                                  height_px, cairo_status_to_string(status)));
  }
  return RgbSurface(std::move(surface));
}

int RgbSurface::width() const { return cairo_image_surface_get_width(surface_.get()); }

int RgbSurface::height() const { return cairo_image_surface_get_height(surface_.get()); }

RgbImage RgbSurface::copyRgb() const {
  cairo_surface_t* surface = surface_.get();
  cairo_surface_flush(surface);
  RgbImage image;
  image.width = width();
  image.height = height();
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

RgbSurface::Pixels RgbSurface::pixels() { return Pixels(surface_.get()); }

RgbSurface::Pixels::Pixels(cairo_surface_t* surface) : surface_(surface) {
  cairo_surface_flush(surface_);
  data_ = cairo_image_surface_get_data(surface_);
  stride_ = cairo_image_surface_get_stride(surface_);
}

RgbSurface::Pixels::~Pixels() { cairo_surface_mark_dirty(surface_); }

std::uint32_t* RgbSurface::Pixels::row(int y) const {
  return reinterpret_cast<std::uint32_t*>(data_ + static_cast<std::ptrdiff_t>(y) * stride_);
}

}  // namespace glarecam::render
