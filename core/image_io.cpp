#include "core/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfThreading.h>
#include <half.h>
#include <libdeflate.h>
#include <png.h>
#include <tiffio.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "core/deflate_compressor.h"
#include "core/exr_zip.h"
#include "core/parallel.h"

namespace glarecam {
namespace fs = std::filesystem;

namespace {

constexpr std::uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::uint8_t kTiffLittle[4] = {'I', 'I', 42, 0};
constexpr std::uint8_t kTiffBig[4] = {'M', 'M', 0, 42};

std::string describe(const fs::path& path) { return path.string(); }

// A reason to refuse a header's size before allocating for it, or nothing.
std::optional<std::string> implausibleSize(std::uint64_t width, std::uint64_t height,
                                           std::uint64_t bytes_per_pixel,
                                           std::uint64_t file_bytes) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width == 0 || height == 0) return "has an empty size (" + size + ")";
  if (width * height > kMaxFramePixels) return "is too large (" + size + ")";
  if (width * height * bytes_per_pixel > file_bytes * kMaxCompressionRatio) {
    return "is truncated: its header announces " + size +
           " pixels, far more than the file can hold";
  }
  return std::nullopt;
}

// ---------------------------------------------------------------- PNG

struct PngErrorState {
  std::jmp_buf jump;
  char message[256] = "corrupt data";
};

void pngError(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof state->message, "%s", message);
  std::longjmp(state->jump, 1);
}
void pngWarning(png_structp, png_const_charp) {}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

struct PngHeader {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0, interlace = 0;
};

// Reads a PNG with libpng's setjmp error protocol. Every object with a destructor is declared
// before setjmp, so a longjmp back into this frame skips no destructor, and values read after
// it (the error message) are not modified between setjmp and the jump.
Result<DecodedFrame> readPng(const fs::path& path, std::FILE* file, std::uint64_t file_bytes) {
  PngErrorState state;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, pngError, pngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_read_struct(&png, &info, nullptr);
    return fail(ErrorCode::kInternal, describe(path) + ": out of memory reading PNG");
  }
  DecodedFrame decoded;
  std::vector<png_bytep> rows;
  PngHeader header;
  std::string problem;
  std::vector<std::uint8_t> bytes8;
  if (setjmp(state.jump)) {
    png_destroy_read_struct(&png, &info, nullptr);
    return badInput(describe(path) + ": corrupt or truncated PNG (" + state.message + ")");
  }
  png_init_io(png, file);
  png_set_user_limits(png, 1u << 20, 1u << 20);
  png_read_info(png, info);
  png_get_IHDR(png, info, &header.width, &header.height, &header.bit_depth, &header.color_type,
               &header.interlace, nullptr, nullptr);
  if (header.color_type != PNG_COLOR_TYPE_GRAY) {
    problem = "is not a single-channel greyscale PNG (colour type " +
              std::to_string(header.color_type) + ")";
  } else if (header.bit_depth != 8 && header.bit_depth != 16) {
    problem =
        "has " + std::to_string(header.bit_depth) + "-bit samples; frames must be 8- or 16-bit";
  } else if (auto size =
                 implausibleSize(header.width, header.height, header.bit_depth / 8, file_bytes)) {
    problem = *size;
  }
  if (!problem.empty()) {
    png_destroy_read_struct(&png, &info, nullptr);
    return badInput(describe(path) + ": " + problem);
  }
  if (header.bit_depth == 16) png_set_swap(png);  // PNG is big-endian; we are not
  if (header.interlace != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
  png_read_update_info(png, info);
  decoded.bit_depth = header.bit_depth;
  decoded.pixels =
      RawFrame::uninitialized(static_cast<int>(header.width), static_cast<int>(header.height));
  if (header.bit_depth == 8) bytes8.resize(static_cast<std::size_t>(header.width) * header.height);
  rows.resize(header.height);
  for (png_uint_32 y = 0; y < header.height; ++y) {
    rows[y] = header.bit_depth == 16
                  ? reinterpret_cast<png_bytep>(decoded.pixels.row(static_cast<int>(y)).data())
                  : bytes8.data() + static_cast<std::size_t>(y) * header.width;
  }
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  if (header.bit_depth == 8) std::copy(bytes8.begin(), bytes8.end(), decoded.pixels.data());
  return decoded;
}

// ---------------------------------------------------------------- PNG writing

// PNG colour types (PNG specification, 11.2.2 IHDR).
constexpr std::uint8_t kPngColourGray = 0, kPngColourRgb = 2;
constexpr std::size_t kPngChunkOverhead = 12;  // length, type, CRC
constexpr std::size_t kPngIhdrBytes = 13;
constexpr std::uint8_t kPngFilterNone = 0;

void putBigEndian32(std::uint8_t* out, std::uint32_t value) {
  out[0] = static_cast<std::uint8_t>(value >> 24);
  out[1] = static_cast<std::uint8_t>(value >> 16);
  out[2] = static_cast<std::uint8_t>(value >> 8);
  out[3] = static_cast<std::uint8_t>(value);
}

// Fills a chunk whose data (`length` bytes) already sits after its 8-byte header at `chunk`:
// the length, the type and the CRC over type and data.
void sealPngChunk(std::uint8_t* chunk, const char (&type)[5], std::size_t length) {
  putBigEndian32(chunk, static_cast<std::uint32_t>(length));
  std::memcpy(chunk + 4, type, 4);
  const std::uint32_t crc = libdeflate_crc32(0, chunk + 4, 4 + length);
  putBigEndian32(chunk + 8 + length, crc);
}

// Encodes rows (8-bit samples, or 16-bit in native order) as a PNG in memory: no row filter and
// one IDAT chunk, compressed by libdeflate in one call (docs/process.md, "Output encodings":
// 2.5 times faster than zlib at the same level, and smaller).
Result<std::vector<std::byte>> encodePng(int width, int height, int bit_depth,
                                         std::uint8_t colour_type,
                                         const std::vector<const std::uint8_t*>& rows,
                                         int deflate_level) {
  const std::size_t samples = colour_type == kPngColourRgb ? 3 : 1;
  const std::size_t row_bytes = static_cast<std::size_t>(width) * samples * (bit_depth / 8);
  std::vector<std::uint8_t> filtered((row_bytes + 1) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    std::uint8_t* line = filtered.data() + static_cast<std::size_t>(y) * (row_bytes + 1);
    line[0] = kPngFilterNone;
    const std::uint8_t* row = rows[static_cast<std::size_t>(y)];
    if (bit_depth == 16) {  // PNG is big-endian
      for (std::size_t i = 0; i < row_bytes; i += 2) {
        line[1 + i] = row[i + 1];
        line[2 + i] = row[i];
      }
    } else {
      std::memcpy(line + 1, row, row_bytes);
    }
  }
  const DeflateCompressor compressor = makeDeflateCompressor(deflate_level);
  if (!compressor) return fail(ErrorCode::kInternal, "out of memory encoding PNG");
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor.get(), filtered.size());
  const std::size_t ihdr = sizeof kPngSignature;
  const std::size_t idat = ihdr + kPngChunkOverhead + kPngIhdrBytes;
  std::vector<std::byte> png(idat + kPngChunkOverhead + bound + kPngChunkOverhead);
  auto* out = reinterpret_cast<std::uint8_t*>(png.data());
  std::copy(std::begin(kPngSignature), std::end(kPngSignature), out);
  std::uint8_t* header = out + ihdr + 8;
  putBigEndian32(header, static_cast<std::uint32_t>(width));
  putBigEndian32(header + 4, static_cast<std::uint32_t>(height));
  header[8] = static_cast<std::uint8_t>(bit_depth);
  header[9] = colour_type;
  header[10] = header[11] = header[12] = 0;  // deflate, adaptive filtering, no interlace
  sealPngChunk(out + ihdr, "IHDR", kPngIhdrBytes);
  const std::size_t compressed = libdeflate_zlib_compress(compressor.get(), filtered.data(),
                                                          filtered.size(), out + idat + 8, bound);
  if (compressed == 0 || compressed > std::numeric_limits<std::int32_t>::max())
    return fail(ErrorCode::kInternal, "PNG encoder failed: image too large for one IDAT chunk");
  sealPngChunk(out + idat, "IDAT", compressed);
  const std::size_t iend = idat + kPngChunkOverhead + compressed;
  sealPngChunk(out + iend, "IEND", 0);
  png.resize(iend + kPngChunkOverhead);
  return png;
}

// ---------------------------------------------------------------- TIFF

thread_local std::string tiff_last_error;

void tiffErrorHandler(const char* module, const char* format, va_list args) {
  char buffer[256];
  std::vsnprintf(buffer, sizeof buffer, format, args);
  tiff_last_error = (module ? std::string(module) + ": " : std::string()) + buffer;
}
void tiffWarningHandler(const char*, const char*, va_list) {}

void installTiffHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    TIFFSetErrorHandler(tiffErrorHandler);
    TIFFSetWarningHandler(tiffWarningHandler);
  });
}

struct TiffCloser {
  void operator()(TIFF* tiff) const { TIFFClose(tiff); }
};
using TiffPtr = std::unique_ptr<TIFF, TiffCloser>;

Result<DecodedFrame> readTiff(const fs::path& path, std::uint64_t file_bytes) {
  installTiffHandlers();
  tiff_last_error.clear();
  TiffPtr tiff(TIFFOpen(path.c_str(), "r"));
  auto tiffFailure = [&](const std::string& what) {
    return badInput(describe(path) + ": " + what +
                    (tiff_last_error.empty() ? "" : " (" + tiff_last_error + ")"));
  };
  if (!tiff) return tiffFailure("not a readable TIFF");
  std::uint32_t width = 0, height = 0;
  std::uint16_t samples = 1, bits = 0, format = SAMPLEFORMAT_UINT,
                photometric = PHOTOMETRIC_MINISBLACK;
  TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &width);
  TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &height);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetField(tiff.get(), TIFFTAG_PHOTOMETRIC, &photometric);
  if (samples != 1 || photometric != PHOTOMETRIC_MINISBLACK) {
    return badInput(describe(path) + ": is not a single-channel greyscale TIFF (" +
                    std::to_string(samples) + " samples per pixel)");
  }
  if ((bits != 8 && bits != 16) || format != SAMPLEFORMAT_UINT) {
    return badInput(describe(path) + ": has " + std::to_string(bits) +
                    "-bit samples; frames must be unsigned 8- or 16-bit");
  }
  if (auto size = implausibleSize(width, height, bits / 8, file_bytes))
    return badInput(describe(path) + ": " + *size);
  if (TIFFIsTiled(tiff.get()))
    return badInput(describe(path) + ": tiled TIFF is not supported; write strips");
  DecodedFrame decoded{RawFrame::uninitialized(static_cast<int>(width), static_cast<int>(height)),
                       bits};
  std::vector<std::uint8_t> line(static_cast<std::size_t>(TIFFScanlineSize(tiff.get())));
  if (line.size() < static_cast<std::size_t>(width) * (bits / 8))
    return tiffFailure("inconsistent scanline size");
  for (std::uint32_t y = 0; y < height; ++y) {
    if (TIFFReadScanline(tiff.get(), line.data(), y, 0) < 0) {
      return tiffFailure("corrupt or truncated TIFF at row " + std::to_string(y));
    }
    auto row = decoded.pixels.row(static_cast<int>(y));
    if (bits == 16) {
      std::memcpy(row.data(), line.data(), row.size_bytes());
    } else {
      std::copy(line.begin(), line.begin() + width, row.begin());
    }
  }
  return decoded;
}

// ---------------------------------------------------------------- EXR

// The threads an EXR file may use (core/parallel.h): OpenEXR's pool, made once with a thread per
// core, takes as many line-buffer tasks as the file's thread count; 0 keeps all the work on the
// calling thread and starts no pool at all.
int exrThreads() {
  const unsigned threads = availableThreads();
  if (threads <= 1) return 0;
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(static_cast<int>(defaultThreadCount())); });
  return static_cast<int>(threads);
}

std::vector<std::uint8_t> readMagic(std::FILE* file) {
  std::vector<std::uint8_t> magic(8, 0);
  magic.resize(std::fread(magic.data(), 1, magic.size(), file));
  std::rewind(file);
  return magic;
}

bool startsWith(const std::vector<std::uint8_t>& bytes, std::span<const std::uint8_t> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

}  // namespace

Result<DecodedFrame> readRawFrame(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    return badInput(describe(path) + ": frame file is missing or not a regular file");
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) return badInput(describe(path) + ": cannot open frame: " + std::strerror(errno));
  auto magic = readMagic(file.get());
  if (magic.empty()) return badInput(describe(path) + ": frame file is empty");
  const std::uint64_t file_bytes = fs::file_size(path, ec);
  try {
    if (startsWith(magic, kPngSignature)) return readPng(path, file.get(), file_bytes);
    if (startsWith(magic, kTiffLittle) || startsWith(magic, kTiffBig))
      return readTiff(path, file_bytes);
  } catch (const std::bad_alloc&) {
    return ioError(describe(path) + ": not enough memory to decode the frame");
  }
  return badInput(describe(path) + ": not a PNG or TIFF image");
}

Result<FrameSize> readFrameSize(const fs::path& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) return badInput(describe(path) + ": cannot open frame: " + std::strerror(errno));
  // PNG: the signature, then the IHDR chunk (length, type, width and height big-endian).
  constexpr std::size_t kPngHeaderBytes = 24;
  std::uint8_t head[kPngHeaderBytes] = {};
  const std::size_t got = std::fread(head, 1, sizeof head, file.get());
  const auto bigEndian = [&](std::size_t at) {
    return std::uint32_t{head[at]} << 24 | std::uint32_t{head[at + 1]} << 16 |
           std::uint32_t{head[at + 2]} << 8 | std::uint32_t{head[at + 3]};
  };
  std::uint32_t width = 0, height = 0;
  const std::span<const std::uint8_t> bytes(head, got);
  const auto startsWithBytes = [&](std::span<const std::uint8_t> prefix) {
    return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
  };
  if (startsWithBytes(kPngSignature)) {
    if (got < kPngHeaderBytes || std::memcmp(head + 12, "IHDR", 4) != 0)
      return badInput(describe(path) + ": corrupt PNG header");
    width = bigEndian(16);
    height = bigEndian(20);
  } else if (startsWithBytes(kTiffLittle) || startsWithBytes(kTiffBig)) {
    installTiffHandlers();
    TiffPtr tiff(TIFFOpen(path.c_str(), "r"));
    if (!tiff) return badInput(describe(path) + ": not a readable TIFF");
    TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &width);
    TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &height);
  } else {
    return badInput(describe(path) + ": not a PNG or TIFF image");
  }
  if (width == 0 || height == 0 || std::uint64_t{width} * height > kMaxFramePixels)
    return badInput(describe(path) + ": implausible frame size " + std::to_string(width) + "x" +
                    std::to_string(height));
  return FrameSize{static_cast<int>(width), static_cast<int>(height)};
}

Result<std::vector<std::byte>> encodePngGray(const RawFrame& frame, int bit_depth,
                                             int deflate_level) {
  std::vector<std::uint8_t> bytes8;
  std::vector<const std::uint8_t*> rows(static_cast<std::size_t>(frame.height()));
  if (bit_depth == 8) {
    bytes8.resize(frame.pixelCount());
    for (std::size_t i = 0; i < bytes8.size(); ++i)
      bytes8[i] = static_cast<std::uint8_t>(std::min<int>(frame.data()[i], 255));
  }
  for (int y = 0; y < frame.height(); ++y) {
    rows[static_cast<std::size_t>(y)] =
        bit_depth == 8 ? bytes8.data() + static_cast<std::size_t>(y) * frame.width()
                       : reinterpret_cast<const std::uint8_t*>(frame.row(y).data());
  }
  return encodePng(frame.width(), frame.height(), bit_depth, kPngColourGray, rows, deflate_level);
}

Status writePngGray(const fs::path& path, const RawFrame& frame, int bit_depth) {
  auto bytes = encodePngGray(frame, bit_depth);
  if (!bytes) return std::unexpected(withContext(bytes.error(), describe(path)));
  return writeFileAtomic(path, *bytes);
}

Status writePngRgb(const fs::path& path, int width, int height, std::span<const std::uint8_t> rgb,
                   int deflate_level) {
  if (rgb.size() != static_cast<std::size_t>(width) * height * 3) {
    return fail(ErrorCode::kInternal,
                describe(path) + ": RGB buffer does not match the image size");
  }
  std::vector<const std::uint8_t*> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[static_cast<std::size_t>(y)] = rgb.data() + static_cast<std::size_t>(y) * width * 3;
  auto bytes = encodePng(width, height, 8, kPngColourRgb, rows, deflate_level);
  if (!bytes) return std::unexpected(withContext(bytes.error(), describe(path)));
  return writeFileAtomic(path, *bytes);
}

namespace {

bool writeTiffStrips(TIFF* tiff, const RawFrame& frame, TiffCompression compression) {
  constexpr std::uint32_t kRowsPerStrip = 64;
  constexpr int kFastestLevel = 1;  // measured in docs/process.md, "Output encodings"
  switch (compression) {
    case TiffCompression::kDeflate:
      TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
      TIFFSetField(tiff, TIFFTAG_ZIPQUALITY, kFastestLevel);
      break;
    case TiffCompression::kZstd:
      TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_ZSTD);
      TIFFSetField(tiff, TIFFTAG_ZSTD_LEVEL, kFastestLevel);
      break;
    case TiffCompression::kNone:
      TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_NONE);
      break;
  }
  TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(frame.width()));
  TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(frame.height()));
  TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 1);
  TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, 16);
  TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, kRowsPerStrip);
  for (int y = 0; y < frame.height(); ++y) {
    auto* row = const_cast<std::uint16_t*>(frame.row(y).data());
    if (TIFFWriteScanline(tiff, row, static_cast<std::uint32_t>(y), 0) < 0) return false;
  }
  return TIFFFlush(tiff) == 1;  // TIFFClose cannot report a failed flush
}

}  // namespace

Status writeTiffGray16(const fs::path& path, const RawFrame& frame, TiffCompression compression) {
  installTiffHandlers();
  fs::path temp;
  GLARECAM_ASSIGN(temp, createTemporarySibling(path));
  bool written = false;
  {
    TiffPtr tiff(TIFFOpen(temp.c_str(), "w"));
    written = tiff && writeTiffStrips(tiff.get(), frame, compression);
  }
  if (!written) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return ioError(describe(path) + ": cannot write TIFF (" + tiff_last_error + ")");
  }
  return commitTemporary(temp, path);
}

namespace {

static_assert(static_cast<int>(ExrPixelType::kUint) == Imf::UINT &&
              static_cast<int>(ExrPixelType::kHalf) == Imf::HALF &&
              static_cast<int>(ExrPixelType::kFloat) == Imf::FLOAT);

Imf::Compression exrCompression(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::kPiz:
      return Imf::PIZ_COMPRESSION;
    case ExrCompression::kZip:
      break;
  }
  return Imf::ZIP_COMPRESSION;
}

// value rounded to nearest with its low 8 mantissa bits zero (ExrStorage::kFloat24). A carry into
// the exponent is the correct rounding up to the next power of two.
float roundTo24Bits(float value) {
  constexpr std::uint32_t kExponentMask = 0x7f800000u;
  constexpr std::uint32_t kDroppedBits = 0xffu, kHalfDropped = 0x80u;
  auto bits = std::bit_cast<std::uint32_t>(value);
  if ((bits & kExponentMask) == kExponentMask) return value;  // NaN and infinities as they are
  bits = (bits + kHalfDropped) & ~kDroppedBits;
  return std::bit_cast<float>(bits);
}

ExrPixelType exrPixelType(ExrStorage storage) {
  switch (storage) {
    case ExrStorage::kHalf:
      return ExrPixelType::kHalf;
    case ExrStorage::kUint:
      return ExrPixelType::kUint;
    case ExrStorage::kFloat24:
    case ExrStorage::kFloat:
      break;
  }
  return ExrPixelType::kFloat;
}

std::uint32_t exrUint(std::uint8_t value) { return value; }
std::uint32_t exrUint(float pixel) {
  const double value = pixel;  // NaN fails every comparison: 0
  constexpr double kMax = std::numeric_limits<std::uint32_t>::max();
  return value > 0 ? static_cast<std::uint32_t>(std::round(std::min(value, kMax))) : 0u;
}

// n pixels in the type they are stored as (OpenEXR converts only when reading), to `out`. `out`
// need not be aligned for that type: a row of the packed layout puts a channel after an odd
// number of half pixels (an odd width) at any byte, so each value is copied, not stored
// through a typed pointer.
template <typename T>
void convertExrPixels(const T* pixels, std::size_t n, ExrStorage storage, std::byte* out) {
  const auto put = [&out](std::size_t i, auto value) {
    std::memcpy(out + i * sizeof(value), &value, sizeof(value));
  };
  switch (storage) {
    case ExrStorage::kHalf:
      for (std::size_t i = 0; i < n; ++i) put(i, half(static_cast<float>(pixels[i])));
      return;
    case ExrStorage::kUint:
      for (std::size_t i = 0; i < n; ++i) put(i, exrUint(pixels[i]));
      return;
    case ExrStorage::kFloat24:
    case ExrStorage::kFloat:
      break;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto value = static_cast<float>(pixels[i]);
    put(i, storage == ExrStorage::kFloat24 ? roundTo24Bits(value) : value);
  }
}

// A float channel stored as kFloat needs no copy.
template <typename T>
bool storedAsIs(ExrStorage storage) {
  return std::is_same_v<T, float> && storage == ExrStorage::kFloat;
}

// A channel's pixels in the type it is stored as, whole, for OpenEXR's encoders.
struct ExrPixels {
  std::unique_ptr<std::byte[]> converted;  // uninitialised: every byte is written

  template <typename T>
  Imf::Slice slice(const Image<T>& image, ExrStorage storage) {
    const std::size_t n = image.pixelCount();
    const auto type = exrPixelType(storage);
    const std::size_t bytes = static_cast<std::size_t>(exrPixelBytes(type));
    const auto row_bytes = bytes * static_cast<std::size_t>(image.width());
    const auto imf_type = static_cast<Imf::PixelType>(type);
    if (storedAsIs<T>(storage)) {
      auto* base = const_cast<char*>(reinterpret_cast<const char*>(image.data()));
      return {imf_type, base, bytes, row_bytes};
    }
    converted.reset(new std::byte[n * bytes]);
    convertExrPixels(image.data(), n, storage, converted.get());
    return {imf_type, reinterpret_cast<char*>(converted.get()), bytes, row_bytes};
  }
};

// A channel for core/exr_zip.h: each row converted as the encoder asks for it, no whole copy.
ExrZipChannel zipChannel(const ExrChannel& channel) {
  return std::visit(
      [&](const auto* image) {
        using T = std::remove_cvref_t<decltype(*image->data())>;
        const ExrStorage storage = channel.storage;
        return ExrZipChannel{channel.name, exrPixelType(storage),
                             [image, storage](int y, std::byte* out) {
                               const auto row = image->row(y);
                               if (storedAsIs<T>(storage)) {
                                 std::memcpy(out, row.data(), row.size_bytes());
                               } else {
                                 convertExrPixels(row.data(), row.size(), storage, out);
                               }
                             }};
      },
      channel.image);
}

// A channel's width and height, whichever its pixel type.
std::pair<int, int> channelSize(const ExrChannel& channel) {
  return std::visit([](const auto* image) { return std::pair(image->width(), image->height()); },
                    channel.image);
}

bool hasPixels(const ExrChannel& channel) {
  return std::visit([](const auto* image) { return image != nullptr; }, channel.image);
}

}  // namespace

Status writeExr(const fs::path& path, std::span<const ExrChannel> channels,
                ExrCompression compression) {
  if (channels.empty() || !std::all_of(channels.begin(), channels.end(), hasPixels))
    return fail(ErrorCode::kInternal, describe(path) + ": no EXR channel");
  const auto [width, height] = channelSize(channels.front());
  for (const ExrChannel& channel : channels) {
    if (channelSize(channel) != std::pair(width, height))
      return fail(ErrorCode::kInternal, describe(path) + ": EXR channels differ in size");
  }
  try {
    if (compression == ExrCompression::kZip) {  // through libdeflate (core/exr_zip.h)
      std::vector<ExrZipChannel> zip_channels;
      for (const ExrChannel& channel : channels) zip_channels.push_back(zipChannel(channel));
      auto bytes = encodeExrZip(width, height, zip_channels);
      if (!bytes) return std::unexpected(withContext(bytes.error(), describe(path)));
      return writeFileAtomic(path, *bytes);
    }
    Imf::Header header(width, height);
    header.compression() = exrCompression(compression);
    Imf::FrameBuffer buffer;
    std::vector<ExrPixels> pixels(channels.size());
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const Imf::Slice slice = std::visit(
          [&](const auto* image) { return pixels[c].slice(*image, channels[c].storage); },
          channels[c].image);
      header.channels().insert(channels[c].name, Imf::Channel(slice.type));
      buffer.insert(channels[c].name, slice);
    }
    Imf::StdOSStream stream;
    {
      Imf::OutputFile file(stream, header, exrThreads());
      file.setFrameBuffer(buffer);
      file.writePixels(height);
    }  // the OutputFile destructor writes the line-offset table (swallowing any error): the
       // bytes go to the file only after it, through writeFileAtomic, which reports every error
    const std::string bytes = stream.str();
    return writeFileAtomic(path, std::string_view(bytes));
  } catch (const std::exception& e) {
    return fail(ErrorCode::kInternal, describe(path) + ": cannot encode EXR: " + e.what());
  }
}

Status writeExr(const fs::path& path, const FloatImage& image, const std::string& channel,
                ExrCompression compression) {
  ExrChannel only{channel, &image};
  return writeExr(path, std::span(&only, 1), compression);
}

Result<FloatImage> readExr(const fs::path& path, const std::string& channel) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return badInput(describe(path) + ": EXR file is missing");
  try {
    Imf::InputFile file(path.c_str(), exrThreads());
    const auto& channels = file.header().channels();
    std::string name = channel;
    if (!channels.findChannel(name)) {
      auto it = channels.begin();
      if (it == channels.end() || ++channels.begin() != channels.end()) {
        return badInput(describe(path) + ": EXR has no channel \"" + channel +
                        "\" and more than one other");
      }
      name = it.name();
    }
    Imath::Box2i window = file.header().dataWindow();
    int width = window.max.x - window.min.x + 1;
    int height = window.max.y - window.min.y + 1;
    if (width <= 0 || height <= 0 || static_cast<std::uint64_t>(width) * height > kMaxFramePixels) {
      return badInput(describe(path) + ": EXR has an unusable size");
    }
    FloatImage image(width, height);
    char* origin = reinterpret_cast<char*>(image.data()) -
                   (static_cast<std::ptrdiff_t>(window.min.x) +
                    static_cast<std::ptrdiff_t>(window.min.y) * width) *
                       static_cast<std::ptrdiff_t>(sizeof(float));
    Imf::FrameBuffer buffer;
    buffer.insert(name, Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * width));
    file.setFrameBuffer(buffer);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    return badInput(describe(path) + ": unreadable EXR: " + e.what());
  }
}

}  // namespace glarecam
