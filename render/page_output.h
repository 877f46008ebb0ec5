// A page drawn once and written as files: PDF and SVG (vector, the page's size in points) and a
// PNG (raster, kPngPixelsPerPt pixels a point); or a document of several pages, each drawn by
// its own drawing, written as one PDF (a report). Each file is written atomically
// (core/atomic_file.h): drawn into a hidden temporary sibling and renamed into place, so that a
// reader sees the old file or the complete new one, never half of one. A drawing that fails, or
// a directory that cannot be written, is a kIo error naming the file; the target is then left
// as it was. Lengths are in points (pt, 1/72 in), the drawing's user units.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"

namespace glarecam::render {

class Canvas;

struct PageSize {
  double width_pt = 0, height_pt = 0;
};

inline constexpr PageSize kA4Landscape{842, 595};  // 297 × 210 mm
inline constexpr double kPngPixelsPerPt = 2;       // the raster previews at 144 dpi

// Draws the whole page on a canvas whose user units are points (the PNG's canvas is scaled).
using PageDrawing = std::function<void(Canvas&)>;

struct PdfMetadata {
  std::string title, creator;
};

Status writePdfPage(const std::filesystem::path& file, PageSize size, const PageDrawing& draw,
                    const PdfMetadata& metadata);
// One PDF of pages.size() pages of one size, page i drawn by pages[i] on a canvas of its own (a
// drawing starts from Cairo's defaults, whatever the one before it left). kBadInput, with
// nothing written, for no pages; kIo naming the file when a drawing fails (the first failing
// page is named) or the file cannot be written.
Status writePdfPages(const std::filesystem::path& file, PageSize size,
                     const std::vector<PageDrawing>& pages, const PdfMetadata& metadata);
Status writeSvgPage(const std::filesystem::path& file, PageSize size, const PageDrawing& draw);
Status writePngPage(const std::filesystem::path& file, PageSize size, const PageDrawing& draw);

}  // namespace glarecam::render
