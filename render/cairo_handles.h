// Owning handles for Cairo's two reference-counted objects, a drawing context (cairo_t) and a
// surface (cairo_surface_t). A handle holds one reference and drops it when it goes; handles
// move, never copy, so that each reference is dropped exactly once. An empty handle holds none.
//
// Cairo reports a failed creation not with a null pointer but with an object in an error
// state that every later call ignores; createContext (and RgbSurface::create, rgb_surface.h)
// turn that state into an Error. The Cairo types are only declared here: the headers that hold
// handles (canvas.h, rgb_surface.h) do not need <cairo.h>, which only the toolkit's .cpp files
// include.
#pragma once

#include <memory>

#include "core/error.h"

typedef struct _cairo cairo_t;  // as <cairo.h> declares them
typedef struct _cairo_surface cairo_surface_t;

namespace glarecam::render {

// Drops one reference to `object` through Destroy (cairo_destroy, cairo_surface_destroy).
template <typename T, void (*Destroy)(T*)>
struct DropReference {
  void operator()(T* object) const { Destroy(object); }
};

template <typename T, void (*Destroy)(T*)>
using CairoHandle = std::unique_ptr<T, DropReference<T, Destroy>>;

void destroyCairoContext(cairo_t* context);
void destroyCairoSurface(cairo_surface_t* surface);

using CairoContext = CairoHandle<cairo_t, destroyCairoContext>;
using CairoSurface = CairoHandle<cairo_surface_t, destroyCairoSurface>;

// A context drawing on `target`, which it keeps alive by a reference of its own.
Result<CairoContext> createContext(cairo_surface_t* target);

// The first error of what has been drawn with `context` (Cairo keeps only the first).
Status drawingStatus(cairo_t* context);

}  // namespace glarecam::render
