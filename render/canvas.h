// A drawing context: the one door to Cairo for everything that draws. A Canvas owns a Cairo
// context (cairo_t) on a surface (an RgbSurface, or a page of page_output.h) and offers exactly
// the operations the toolkit and the pictures draw with: a path (move, line, rectangle, arc),
// stroking and filling it, line width, joins, caps and dashes, a source colour, the user space's
// transformation (translate, scale, rotate), clipping, text in a font face, and painting an 8-bit
// RGB image. Coordinates are in user units (points on a page, pixels on a picture), x to the
// right, y down; angles are in radians, as Cairo's.
//
// A canvas moves, never copies, so that its context is dropped once. save() returns a guard that
// restores the transformation, clip and style when it goes. Cairo keeps the first error of what
// is drawn and ignores every later call; status() reports it.
#pragma once

#include <span>
#include <string>

#include "core/error.h"
#include "render/cairo_handles.h"
#include "render/colour.h"
#include "render/page_geometry.h"

namespace glarecam::render {

class RgbSurface;
struct RgbImage;

enum class LineJoin { kMiter, kRound };
enum class LineCap { kButt, kRound };

class Canvas {
 public:
  // A canvas drawing on `surface`, which it keeps alive by a reference of its own.
  static Result<Canvas> onSurface(RgbSurface& surface);
  // A canvas on a context made in render/ (a page's, page_output.cpp).
  explicit Canvas(CairoContext context);

  // The state saved by save(), restored when the guard goes (scoped, neither copied nor moved).
  class [[nodiscard]] Saved {
   public:
    ~Saved();
    Saved(const Saved&) = delete;
    Saved& operator=(const Saved&) = delete;

   private:
    friend class Canvas;
    explicit Saved(Canvas& canvas);
    Canvas& canvas_;
  };
  Saved save();

  // The path.
  void moveTo(Point p);
  void lineTo(Point p);
  void newSubPath();
  void rectangle(Point top_left, double width, double height);
  void rectangle(const Box& box) { rectangle({box.x0, box.y0}, box.width(), box.height()); }
  void arc(Point centre, double radius, double from_rad, double to_rad);

  // Drawing the path (the *Preserve forms keep it for the next operation), painting the whole
  // clip, clipping to the path.
  void stroke();
  void strokePreserve();
  void fill();
  void fillPreserve();
  void paint();
  void clip();

  // The source and the line.
  void setColour(const Rgb& colour, double alpha = 1);  // alpha: opacity, 0 to 1
  void setLineWidth(double width);
  void setLineJoin(LineJoin join);
  void setLineCap(LineCap cap);
  // Lengths of dashes and gaps in turn, from the path's start; empty: solid.
  void setDash(std::span<const double> pattern);

  // The user space.
  void translate(double dx, double dy);
  void scale(double sx, double sy);
  void rotate(double angle_rad);
  // A distance in device units (pixels of a raster) as user units.
  Point deviceToUserDistance(Point device) const;
  // The current clip's bounding box in user units.
  Box clipExtents() const;

  // Text (text.h chooses the family and sizes): the font for what follows, the advance of `text`
  // in it, `text` drawn from the current point, or added to the path as outlines. UTF-8.
  void selectFont(const char* family, bool bold, double size);
  double textAdvance(const std::string& text);
  void showText(const std::string& text);
  void textPath(const std::string& text);

  // `image` with its top left corner at the user origin, one pixel a user unit, each pixel a
  // sharp square however the user space is scaled (nearest filter).
  void paintImage(const RgbImage& image);

  // The first error of what has been drawn (Cairo keeps only the first).
  Status status() const;

 private:
  CairoContext context_;
};

}  // namespace glarecam::render
