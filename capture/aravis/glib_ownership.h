// Ownership of GLib objects for the Aravis backend: every GError is owned and turned into one
// line of text, every GObject released by a std::unique_ptr. Included only by capture/aravis/.
#pragma once

#include <glib-object.h>

#include <memory>
#include <string>
#include <string_view>

namespace glarecam::capture::aravis {

struct GObjectUnref {
  void operator()(gpointer object) const {
    if (object != nullptr) g_object_unref(object);
  }
};
template <typename T>
using GObjectPtr = std::unique_ptr<T, GObjectUnref>;

// Collects the GError of one call: `call(..., error.out())`, then `if (error) ...`.
class OwnedError {
 public:
  OwnedError() = default;
  ~OwnedError() { reset(); }
  OwnedError(const OwnedError&) = delete;
  OwnedError& operator=(const OwnedError&) = delete;

  GError** out() {
    reset();
    return &error_;
  }
  explicit operator bool() const { return error_ != nullptr; }
  std::string message() const {
    return error_ != nullptr && error_->message != nullptr ? error_->message : "unknown error";
  }
  bool matches(GQuark domain, gint code) const {
    return g_error_matches(error_, domain, code) != FALSE;
  }
  void reset() {
    if (error_ != nullptr) g_error_free(error_);
    error_ = nullptr;
  }

 private:
  GError* error_ = nullptr;
};

// A NULL-terminated or counted array of strings that Aravis hands over with g_free ownership of
// the array only (the strings stay Aravis's).
struct GFreeArray {
  void operator()(const char** array) const { g_free(static_cast<gpointer>(array)); }
};
using StringArray = std::unique_ptr<const char*, GFreeArray>;

}  // namespace glarecam::capture::aravis
