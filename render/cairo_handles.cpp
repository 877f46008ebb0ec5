#include "render/cairo_handles.h"

#include <cairo.h>
#include <fmt/format.h>

namespace glarecam::render {

void destroyCairoContext(cairo_t* context) { cairo_destroy(context); }

void destroyCairoSurface(cairo_surface_t* surface) { cairo_surface_destroy(surface); }

Result<CairoContext> createContext(cairo_surface_t* target) {
  CairoContext context(cairo_create(target));
  GLARECAM_CHECK(drawingStatus(context.get()));
  return context;
}

Status drawingStatus(cairo_t* context) {
  const cairo_status_t status = cairo_status(context);
  if (status != CAIRO_STATUS_SUCCESS)
    return fail(ErrorCode::kInternal, fmt::format("drawing: {}", cairo_status_to_string(status)));
  return {};
}

}  // namespace glarecam::render
