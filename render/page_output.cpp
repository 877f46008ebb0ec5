#include "render/page_output.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include <cmath>
#include <system_error>

#include "core/atomic_file.h"
#include "render/canvas.h"

namespace glarecam::render {
namespace {

namespace fs = std::filesystem;

// Draws the page on surface, `scale` device units per point; the drawing's first error.
cairo_status_t drawOn(cairo_surface_t* surface, const PageDrawing& draw, double scale) {
  CairoContext context(cairo_create(surface));
  cairo_t* const cr = context.get();
  Canvas canvas(std::move(context));
  canvas.scale(scale, scale);
  draw(canvas);
  return cairo_status(cr);
}

// Draws on a vector surface writing `file`, and finishes it (which writes the file).
cairo_status_t drawVector(CairoSurface surface, const PageDrawing& draw) {
  const cairo_status_t drawn = drawOn(surface.get(), draw, 1);
  cairo_surface_finish(surface.get());
  return drawn != CAIRO_STATUS_SUCCESS ? drawn : cairo_surface_status(surface.get());
}

// Renders into a temporary sibling of target and renames it into place.
Status writeAtomically(const fs::path& target,
                       const std::function<cairo_status_t(const fs::path&)>& render) {
  fs::path temp;
  GLARECAM_ASSIGN(temp, createTemporarySibling(target));
  const cairo_status_t status = render(temp);
  if (status != CAIRO_STATUS_SUCCESS) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return ioError(fmt::format("{}: {}", target.string(), cairo_status_to_string(status)));
  }
  return commitTemporary(temp, target);
}

}  // namespace

Status writePdfPage(const fs::path& file, PageSize size, const PageDrawing& draw,
                    const PdfMetadata& metadata) {
  return writeAtomically(file, [&](const fs::path& temp) {
    CairoSurface surface(cairo_pdf_surface_create(temp.c_str(), size.width_pt, size.height_pt));
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, metadata.title.c_str());
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR,
                                   metadata.creator.c_str());
    return drawVector(std::move(surface), draw);
  });
}

Status writePdfPages(const fs::path& file, PageSize size, const std::vector<PageDrawing>& pages,
                     const PdfMetadata& metadata) {
  if (pages.empty())
    return badInput(fmt::format("{}: a PDF needs at least one page", file.string()));
  std::size_t failed_page = 0;
  const Status written = writeAtomically(file, [&](const fs::path& temp) {
    CairoSurface surface(cairo_pdf_surface_create(temp.c_str(), size.width_pt, size.height_pt));
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, metadata.title.c_str());
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR,
                                   metadata.creator.c_str());
    for (std::size_t i = 0; i < pages.size(); ++i) {
      // Each page on a context of its own, shown (emitted) before the next one starts.
      CairoContext context(cairo_create(surface.get()));
      cairo_t* const cr = context.get();
      cairo_status_t status = CAIRO_STATUS_SUCCESS;
      {
        Canvas canvas(std::move(context));
        pages[i](canvas);
        cairo_show_page(cr);
        status = cairo_status(cr);
      }
      if (status != CAIRO_STATUS_SUCCESS) {
        failed_page = i + 1;
        cairo_surface_finish(surface.get());
        return status;
      }
    }
    cairo_surface_finish(surface.get());
    return cairo_surface_status(surface.get());
  });
  if (!written && failed_page > 0)
    return ioError(
        fmt::format("{} (page {} of {})", written.error().message, failed_page, pages.size()));
  return written;
}

Status writeSvgPage(const fs::path& file, PageSize size, const PageDrawing& draw) {
  return writeAtomically(file, [&](const fs::path& temp) {
    CairoSurface surface(cairo_svg_surface_create(temp.c_str(), size.width_pt, size.height_pt));
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PT);
    return drawVector(std::move(surface), draw);
  });
}

Status writePngPage(const fs::path& file, PageSize size, const PageDrawing& draw) {
  return writeAtomically(file, [&](const fs::path& temp) {
    const CairoSurface surface(cairo_image_surface_create(
        CAIRO_FORMAT_RGB24, static_cast<int>(std::lround(size.width_pt * kPngPixelsPerPt)),
        static_cast<int>(std::lround(size.height_pt * kPngPixelsPerPt))));
    const cairo_status_t drawn = drawOn(surface.get(), draw, kPngPixelsPerPt);
    if (drawn != CAIRO_STATUS_SUCCESS) return drawn;
    return cairo_surface_write_to_png(surface.get(), temp.c_str());
  });
}

}  // namespace glarecam::render
