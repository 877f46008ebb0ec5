// Image<T>: a dense, row-major, single-channel image owning its pixels. Pixel (0, 0) is the
// top-left pixel, x grows right and y down; pixel centres sit at integer coordinates.
// RawFrame holds a camera's unprocessed values (up to 16 bits); FloatImage holds luminance in
// cd/m² or any other per-pixel float quantity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/memory.h"

namespace glarecam {

// std::allocator, except that
// - an element made without a value is default-initialised: for pixel types, left as it is.
//   Image::uninitialized() uses it for pixels a decoder writes at once, which spares a pass over
//   memory as large as the image;
// - a large block asks for transparent huge pages (core/memory.h), so that an image faults in a
//   2 MiB page at a time.
template <typename T>
struct PixelAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = PixelAllocator<U>;
  };
  using std::allocator<T>::allocator;
  T* allocate(std::size_t n) {
    T* block = std::allocator<T>::allocate(n);
    adviseHugePages(block, n * sizeof(T));
    return block;
  }
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    std::construct_at(p, std::forward<Args>(args)...);
  }
};

template <typename T>
class Image {
 public:
  Image() = default;
  Image(int width, int height, T fill = T{})
      : width_(width), height_(height), pixels_(static_cast<std::size_t>(width) * height, fill) {}

  // An image whose pixels hold whatever the memory held: for a caller that writes every pixel
  // before reading any (a decoder).
  static Image uninitialized(int width, int height) {
    Image image;
    image.width_ = width;
    image.height_ = height;
    image.pixels_.resize(static_cast<std::size_t>(width) * height);
    return image;
  }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t pixelCount() const { return pixels_.size(); }
  bool empty() const { return pixels_.empty(); }
  bool sameSize(int width, int height) const { return width_ == width && height_ == height; }

  T* data() { return pixels_.data(); }
  const T* data() const { return pixels_.data(); }
  std::span<T> row(int y) {
    return {pixels_.data() + offset(0, y), static_cast<std::size_t>(width_)};
  }
  std::span<const T> row(int y) const {
    return {pixels_.data() + offset(0, y), static_cast<std::size_t>(width_)};
  }
  T& at(int x, int y) { return pixels_[offset(x, y)]; }
  const T& at(int x, int y) const { return pixels_[offset(x, y)]; }

 private:
  std::size_t offset(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }

  int width_ = 0;
  int height_ = 0;
  std::vector<T, PixelAllocator<T>> pixels_;
};

using RawFrame = Image<std::uint16_t>;
using FloatImage = Image<float>;
using ByteImage = Image<std::uint8_t>;

}  // namespace glarecam
