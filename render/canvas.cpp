#include "render/canvas.h"

#include <cairo.h>

#include <cstddef>
#include <cstdint>

#include "render/rgb_surface.h"

namespace glarecam::render {

Result<Canvas> Canvas::onSurface(RgbSurface& surface) {
  CairoContext context;
  GLARECAM_ASSIGN(context, createContext(surface.surface_.get()));
  return Canvas(std::move(context));
}

Canvas::Canvas(CairoContext context) : context_(std::move(context)) {}

Canvas::Saved::Saved(Canvas& canvas) : canvas_(canvas) { cairo_save(canvas_.context_.get()); }

Canvas::Saved::~Saved() { cairo_restore(canvas_.context_.get()); }

Canvas::Saved Canvas::save() { return Saved(*this); }

void Canvas::moveTo(Point p) { cairo_move_to(context_.get(), p.x, p.y); }

void Canvas::lineTo(Point p) { cairo_line_to(context_.get(), p.x, p.y); }

void Canvas::newSubPath() { cairo_new_sub_path(context_.get()); }

void Canvas::rectangle(Point top_left, double width, double height) {
  cairo_rectangle(context_.get(), top_left.x, top_left.y, width, height);
}

void Canvas::arc(Point centre, double radius, double from_rad, double to_rad) {
  cairo_arc(context_.get(), centre.x, centre.y, radius, from_rad, to_rad);
}

void Canvas::stroke() { cairo_stroke(context_.get()); }

void Canvas::strokePreserve() { cairo_stroke_preserve(context_.get()); }

void Canvas::fill() { cairo_fill(context_.get()); }

void Canvas::fillPreserve() { cairo_fill_preserve(context_.get()); }

void Canvas::paint() { cairo_paint(context_.get()); }

void Canvas::clip() { cairo_clip(context_.get()); }

void Canvas::setColour(const Rgb& colour, double alpha) {
  cairo_set_source_rgba(context_.get(), colour.r, colour.g, colour.b, alpha);
}

void Canvas::setLineWidth(double width) { cairo_set_line_width(context_.get(), width); }

void Canvas::setLineJoin(LineJoin join) {
  cairo_set_line_join(context_.get(),
                      join == LineJoin::kRound ? CAIRO_LINE_JOIN_ROUND : CAIRO_LINE_JOIN_MITER);
}

void Canvas::setLineCap(LineCap cap) {
  cairo_set_line_cap(context_.get(),
                     cap == LineCap::kRound ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
}

void Canvas::setDash(std::span<const double> pattern) {
  cairo_set_dash(context_.get(), pattern.empty() ? nullptr : pattern.data(),
                 static_cast<int>(pattern.size()), 0);
}

void Canvas::translate(double dx, double dy) { cairo_translate(context_.get(), dx, dy); }

void Canvas::scale(double sx, double sy) { cairo_scale(context_.get(), sx, sy); }

void Canvas::rotate(double angle_rad) { cairo_rotate(context_.get(), angle_rad); }

Point Canvas::deviceToUserDistance(Point device) const {
  cairo_device_to_user_distance(context_.get(), &device.x, &device.y);
  return device;
}

Box Canvas::clipExtents() const {
  Box box;
  cairo_clip_extents(context_.get(), &box.x0, &box.y0, &box.x1, &box.y1);
  return box;
}

void Canvas::selectFont(const char* family, bool bold, double size) {
  cairo_select_font_face(context_.get(), family, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(context_.get(), size);
}

double Canvas::textAdvance(const std::string& text) {
  cairo_text_extents_t extents;
  cairo_text_extents(context_.get(), text.c_str(), &extents);
  return extents.x_advance;
}

void Canvas::showText(const std::string& text) { cairo_show_text(context_.get(), text.c_str()); }

void Canvas::textPath(const std::string& text) { cairo_text_path(context_.get(), text.c_str()); }

void Canvas::paintImage(const RgbImage& image) {
  // A surface Cairo could not allocate is in an error state: painting it puts the drawing in
  // that state, which status() reports.
  const CairoSurface surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height));
  if (cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(surface.get());
    unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < image.height; ++y) {
      auto* out = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
      const std::uint8_t* in = image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3;
      for (int x = 0; x < image.width; ++x)
        out[x] = std::uint32_t{in[3 * x]} << 16 | std::uint32_t{in[3 * x + 1]} << 8 | in[3 * x + 2];
    }
    cairo_surface_mark_dirty(surface.get());
  }
  cairo_set_source_surface(context_.get(), surface.get(), 0, 0);
  cairo_pattern_set_filter(cairo_get_source(context_.get()), CAIRO_FILTER_NEAREST);
  cairo_paint(context_.get());
}

Status Canvas::status() const { return drawingStatus(context_.get()); }

}  // namespace glarecam::render
