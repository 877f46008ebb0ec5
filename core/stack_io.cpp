#include "core/stack_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <system_error>

#include "core/atomic_file.h"
#include "core/image_io.h"
#include "core/json.h"
#include "core/parallel.h"
#include "core/unique_fd.h"

namespace glarecam {
namespace fs = std::filesystem;

namespace {

// Resolves `relative` under `base` and refuses symlinks that lead outside it.
Result<fs::path> resolveInside(const fs::path& base, const std::string& relative,
                               const std::string& where, const std::string& what,
                               const std::string& base_name = "the stack directory") {
  if (!isContainedRelativePath(relative)) {
    return badInput(where + ": " + what + " \"" + relative + "\" escapes " + base_name);
  }
  std::error_code ec;
  fs::path resolved = fs::weakly_canonical(base / relative, ec);
  fs::path root = fs::weakly_canonical(base, ec);
  if (ec)
    return badInput(where + ": cannot resolve " + what + " \"" + relative + "\": " + ec.message());
  auto [root_end, ignored] =
      std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end());
  if (root_end != root.end())
    return badInput(where + ": " + what + " \"" + relative + "\" links outside " + base_name);
  return base / relative;
}

struct ResolvedCalibration {
  Calibration calibration;
  fs::path base_directory;  // where the calibration's relative paths start
  std::string origin;
  std::string where;  // the file it was read from, for messages
};

Result<ResolvedCalibration> resolveCalibration(const fs::path& directory,
                                               const StackManifest& manifest,
                                               const StackReadOptions& options,
                                               const std::string& where) {
  if (options.calibration_file) {
    auto calibration = readCalibrationFile(*options.calibration_file);
    if (!calibration) return std::unexpected(calibration.error());
    return ResolvedCalibration{std::move(*calibration), options.calibration_file->parent_path(),
                               options.calibration_file->string(),
                               options.calibration_file->string()};
  }
  if (manifest.calibration)
    return ResolvedCalibration{*manifest.calibration, directory, "inline", where};
  if (manifest.calibration_path) {
    // A calibration path may point outside the stack (a rig-wide file), unlike frames.
    fs::path path = directory / *manifest.calibration_path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      return badInput(where + ": calibration file \"" + *manifest.calibration_path +
                      "\" does not exist or is not a regular file");
    }
    auto calibration = readCalibrationFile(path);
    if (!calibration) return std::unexpected(calibration.error());
    return ResolvedCalibration{std::move(*calibration), path.parent_path(),
                               *manifest.calibration_path, path.string()};
  }
  if (!options.require_calibration)
    return ResolvedCalibration{Calibration{}, directory, std::string(kNoCalibration), where};
  return badInput(where +
                  ": no calibration: give one inline, as a path, or with --calibration FILE");
}

Status checkFrameSizes(const Stack& stack) {
  const RawFrame& first = stack.frames.front();
  for (std::size_t i = 1; i < stack.frames.size(); ++i) {
    const RawFrame& frame = stack.frames[i];
    if (!frame.sameSize(first.width(), first.height())) {
      return badInput((stack.directory / stack.manifest.frames[i].file).string() + ": frame is " +
                      std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                      " but " + stack.manifest.frames.front().file + " is " +
                      std::to_string(first.width()) + "x" + std::to_string(first.height()) +
                      "; all frames of a stack must have the same size");
    }
  }
  return {};
}

Status decodeFrames(Stack& stack, const std::vector<fs::path>& paths, unsigned threads) {
  std::vector<Result<DecodedFrame>> decoded(paths.size(), badInput("not decoded"));
  // One frame per task; frames are independent, so bands of the frame index are disjoint.
  parallelRows(static_cast<int>(paths.size()), threads, [&](int begin, int end) {
    for (int i = begin; i < end; ++i)
      decoded[static_cast<std::size_t>(i)] = readRawFrame(paths[static_cast<std::size_t>(i)]);
  });
  for (auto& frame : decoded) {
    if (!frame) return std::unexpected(frame.error());
    stack.bit_depths.push_back(frame->bit_depth);
    stack.frames.push_back(std::move(frame->pixels));
  }
  return checkFrameSizes(stack);
}

// Intrinsics are in pixels of the image size they were calibrated at: applied to frames of another
// size every angle is off by the ratio (640x480 intrinsics on a 320x256 stack halve its ellipse).
// A geometry mismatch is never forced.
Status checkIntrinsicsSize(const Stack& stack, const std::string& calibration_where) {
  const Intrinsics& intrinsics = stack.calibration.intrinsics;
  if (!intrinsics.width || !intrinsics.height || stack.frames.empty()) return {};
  const RawFrame& first = stack.frames.front();
  if (*intrinsics.width == first.width() && *intrinsics.height == first.height()) return {};
  return badInput(calibration_where + ": intrinsics were calibrated at " +
                  std::to_string(*intrinsics.width) + "x" + std::to_string(*intrinsics.height) +
                  ", frames are " + std::to_string(first.width()) + "x" +
                  std::to_string(first.height()) +
                  ": every angle would be wrong (calibrate intrinsics at the capture size)");
}

// The absolute path of one of the calibration's images, and the check that an image has the
// frames' size: a calibration image of another size belongs to another camera or binning, and is
// never forced.
struct CalibrationImages {
  const Stack& stack;
  const fs::path& base;
  const std::string& where;

  Result<fs::path> path(const std::string& relative, const std::string& key) const {
    const std::string base_name = stack.calibration_origin == "inline"
                                      ? "the stack directory"
                                      : "the calibration's directory";
    return resolveInside(base, relative, where, key, base_name);
  }

  // The EXR at `relative` (none: nothing), of the frames' size and every value `valid`.
  template <typename Valid>
  Result<std::optional<FloatImage>> exr(const std::optional<std::string>& relative,
                                        const std::string& key, const std::string& what,
                                        Valid valid, const std::string& invalid) const {
    if (!relative) return std::optional<FloatImage>{};
    fs::path file;
    GLARECAM_ASSIGN(file, path(*relative, key));
    FloatImage image;
    GLARECAM_ASSIGN(image, readExr(file));
    GLARECAM_CHECK(checkSize(file, image, what));
    if (!std::all_of(image.data(), image.data() + image.pixelCount(), valid))
      return badInput(file.string() + ": " + what + " has " + invalid);
    return std::optional(std::move(image));
  }

  template <typename T>
  Status checkSize(const fs::path& path, const Image<T>& image, const std::string& what) const {
    const RawFrame& first = stack.frames.front();
    if (image.sameSize(first.width(), first.height())) return {};
    return badInput(path.string() + ": " + what + " is " + std::to_string(image.width()) + "x" +
                    std::to_string(image.height()) + ", frames are " +
                    std::to_string(first.width()) + "x" + std::to_string(first.height()));
  }
};

Status loadFlatField(Stack& stack, const CalibrationImages& images) {
  GLARECAM_ASSIGN(stack.flat_field, images.exr(
                                        stack.calibration.flat_field, "flat_field", "flat field",
                                        [](float v) { return v > 0 && std::isfinite(v); },
                                        "non-positive or non-finite values"));
  return {};
}

// The dark frame's values are DN of the sensor: finite and not negative (a stuck pixel may sit at
// full scale: the hot-pixel map masks it).
Status loadDarkFrame(Stack& stack, const CalibrationImages& images) {
  GLARECAM_ASSIGN(stack.dark_frame_dn, images.exr(
                                           stack.calibration.dark_frame, "dark_frame", "dark frame",
                                           [](float v) { return v >= 0 && std::isfinite(v); },
                                           "negative or non-finite values"));
  return {};
}

Status loadHotPixels(Stack& stack, const CalibrationImages& images) {
  if (!stack.calibration.hot_pixels) return {};
  fs::path path;
  GLARECAM_ASSIGN(path, images.path(*stack.calibration.hot_pixels, "hot_pixels"));
  DecodedFrame map;
  GLARECAM_ASSIGN(map, readRawFrame(path));
  GLARECAM_CHECK(images.checkSize(path, map.pixels, "hot-pixel map"));
  ByteImage& hot = stack.hot_pixels.emplace(map.pixels.width(), map.pixels.height());
  std::transform(map.pixels.data(), map.pixels.data() + map.pixels.pixelCount(), hot.data(),
                 [](std::uint16_t v) { return static_cast<std::uint8_t>(v != 0 ? 255 : 0); });
  return {};
}

}  // namespace

Result<Calibration> readCalibrationFile(const fs::path& path) {
  auto document = readJsonFile(path.string());
  if (!document) return std::unexpected(document.error());
  auto calibration = parseCalibration(*document, path.string());
  if (calibration) {
    std::error_code ec;
    calibration->directory = fs::absolute(path, ec).parent_path();
  }
  if (!calibration && document->is_object() && document->contains("parts") &&
      calibration.error().message.find(" is missing") != std::string::npos) {
    // One part of a calibration (docs/calibration.md): say how to make a whole one.
    calibration.error().message +=
        " (a calibration part: combine the parts with `glarecam calibrate merge`)";
  }
  return calibration;
}

namespace {

Result<Stack> readStackOnce(const fs::path& directory, const StackReadOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec))
    return badInput(directory.string() + ": not a stack directory");
  const fs::path manifest_path = directory / kManifestFileName;
  const std::string where = manifest_path.string();
  if (!fs::exists(manifest_path, ec)) return badInput(where + ": manifest is missing");
  auto document = readJsonFile(where);
  if (!document) return std::unexpected(document.error());

  Stack stack;
  stack.directory = directory;
  GLARECAM_ASSIGN(stack.manifest, parseManifest(*document, where));
  ResolvedCalibration resolved;
  GLARECAM_ASSIGN(resolved, resolveCalibration(directory, stack.manifest, options, where));
  stack.calibration = std::move(resolved.calibration);
  stack.calibration_origin = std::move(resolved.origin);
  for (const FrameSpec& frame : stack.manifest.frames) {
    if (frame.f_number && !stack.calibration.reference_f_number &&
        stack.calibration_origin != kNoCalibration) {
      return badInput(where + ": frame " + frame.file +
                      " gives f_number but the calibration has no reference_f_number");
    }
  }
  std::vector<fs::path> paths;
  for (const FrameSpec& frame : stack.manifest.frames) {
    fs::path path;
    GLARECAM_ASSIGN(path, resolveInside(directory, frame.file, where, "frame"));
    paths.push_back(std::move(path));
  }
  if (!options.decode_frames) return stack;
  GLARECAM_CHECK(
      decodeFrames(stack, paths, options.threads ? options.threads : availableThreads()));
  GLARECAM_CHECK(checkIntrinsicsSize(stack, resolved.where));
  const CalibrationImages images{stack, resolved.base_directory, where};
  GLARECAM_CHECK(loadFlatField(stack, images));
  GLARECAM_CHECK(loadDarkFrame(stack, images));
  GLARECAM_CHECK(loadHotPixels(stack, images));
  return stack;
}

// Pins the directory a path names when reading starts. While the descriptor is open the
// directory's inode cannot be freed and reused, so "the path still names the pinned
// directory" after the read proves that no writer replaced the stack meanwhile (an inode
// number alone could come back: A replaced by B, then B by a new directory that got A's).
class PinnedDirectory {
 public:
  explicit PinnedDirectory(const fs::path& directory)
      : fd_(::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {}
  bool isOpen() const { return fd_.valid(); }
  bool stillNamedBy(const fs::path& directory) const {
    struct stat pinned {
    }, now{};
    if (!fd_.valid() || ::fstat(fd_.get(), &pinned) != 0 || ::stat(directory.c_str(), &now) != 0)
      return false;
    return pinned.st_dev == now.st_dev && pinned.st_ino == now.st_ino;
  }

 private:
  UniqueFd fd_;
};

// A stack replaced while it is read would mix two versions; such reads are retried.
constexpr int kReadAttempts = 5;

}  // namespace

Result<Stack> readStack(const fs::path& directory, const StackReadOptions& options) {
  for (int attempt = 0; attempt < kReadAttempts; ++attempt) {
    const PinnedDirectory pinned(directory);
    auto stack = readStackOnce(directory, options);
    // Not a directory, or one that cannot be opened: the reader's own answer is the message.
    if (!pinned.isOpen() || pinned.stillNamedBy(directory)) return stack;
  }
  return ioError(directory.string() + ": stack was replaced " + std::to_string(kReadAttempts) +
                 " times while being read; try again");
}

bool isStackDirectory(const fs::path& directory) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(directory, ec))) return false;
  if (!fs::is_regular_file(directory / kManifestFileName, ec)) return false;
  auto manifest = readJsonFile((directory / kManifestFileName).string());
  return manifest && manifest->is_object() && manifest->value("schema", "") == kStackSchema;
}

Result<fs::path> stackTarget(const fs::path& requested) {
  if (requested.empty()) return badInput("stack directory: the path is empty");
  std::error_code ec;
  fs::path target = fs::absolute(requested, ec).lexically_normal();
  if (ec) return badInput(requested.string() + ": " + ec.message());
  if (target.filename().empty()) target = target.parent_path();  // "dir/" -> "dir"
  if (target == target.root_path())
    return badInput(requested.string() + ": cannot write a stack over the root directory");
  if (!fs::exists(fs::symlink_status(target, ec))) return target;
  // Replacing deletes what was there: only ever another stack, never someone's files.
  if (!isStackDirectory(target)) {
    return badInput(requested.string() + ": exists and is not a stack (no " +
                    std::string(kManifestFileName) + " of schema " + std::string(kStackSchema) +
                    "); refusing to replace it");
  }
  return target;
}

namespace {

// Everything the writer is given must be consistent and stay inside the stack.
Status checkWriteRequest(const fs::path& directory, const StackWriteRequest& request) {
  const auto& specs = request.manifest.frames;
  const auto internal = [&](const std::string& problem) {
    return fail(ErrorCode::kInternal, directory.string() + ": " + problem);
  };
  if (specs.empty() || specs.size() != request.frames.size()) {
    return internal("manifest lists " + std::to_string(specs.size()) + " frames but " +
                    std::to_string(request.frames.size()) + " were given");
  }
  if (request.bit_depth != 8 && request.bit_depth != 16)
    return internal("frames are written as 8- or 16-bit PNG");
  std::vector<std::string> paths;
  for (const FrameSpec& spec : specs) paths.push_back(spec.file);
  for (const StackAttachment& attachment : request.attachments)
    paths.push_back(attachment.relative_path);
  for (const auto& text : request.text_files) paths.push_back(text.first);
  for (const std::string& path : paths) {
    if (!isContainedRelativePath(path)) return internal("\"" + path + "\" escapes the stack");
  }
  return {};
}

// Frames are encoded in parallel, one per task, each written and fsynced in place.
Status writeFrames(const fs::path& staging, const StackWriteRequest& request) {
  const auto& specs = request.manifest.frames;
  std::vector<Status> written(specs.size());
  parallelRows(static_cast<int>(specs.size()), availableThreads(), [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const auto index = static_cast<std::size_t>(i);
      const fs::path target = staging / specs[index].file;
      std::error_code ec;
      fs::create_directories(target.parent_path(), ec);
      auto bytes = encodePngGray(request.frames[index], request.bit_depth);
      written[index] =
          bytes ? writeFileDurable(target, *bytes) : Status(std::unexpected(bytes.error()));
    }
  });
  for (const Status& status : written) GLARECAM_CHECK(status);
  return {};
}

// Attachments, text files and the manifest, then every subdirectory fsynced.
Status writeManifestAndExtras(const fs::path& staging, const StackWriteRequest& request) {
  for (const StackAttachment& attachment : request.attachments) {
    const fs::path target = staging / attachment.relative_path;
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    fs::copy_file(attachment.source, target, fs::copy_options::overwrite_existing, ec);
    if (ec)
      return ioError(attachment.source.string() + ": cannot copy into stack: " + ec.message());
    GLARECAM_CHECK(fsyncPath(target));
  }
  const auto bytesOf = [](const std::string& text) {
    return std::as_bytes(std::span(text.data(), text.size()));
  };
  for (const auto& [relative_path, content] : request.text_files) {
    GLARECAM_CHECK(writeFileDurable(staging / relative_path, bytesOf(content)));
  }
  const std::string manifest_text = jsonText(toJson(request.manifest));
  GLARECAM_CHECK(writeFileDurable(staging / kManifestFileName, bytesOf(manifest_text)));
  std::error_code ec;
  for (const auto& entry : fs::recursive_directory_iterator(staging, ec)) {
    if (entry.is_directory()) GLARECAM_CHECK(fsyncPath(entry.path()));
  }
  return {};
}

}  // namespace

Status writeStack(const fs::path& requested_directory, const StackWriteRequest& request) {
  fs::path directory;
  GLARECAM_ASSIGN(directory, stackTarget(requested_directory));
  GLARECAM_CHECK(checkWriteRequest(directory, request));
  auto staging = StagingDirectory::create(directory);
  if (!staging) return std::unexpected(staging.error());
  if (request.may_replace) {
    staging->setReplaceCheck(isStackDirectory);
  } else {
    staging->forbidReplacing();
  }
  GLARECAM_CHECK(writeFrames(staging->path(), request));
  GLARECAM_CHECK(writeManifestAndExtras(staging->path(), request));
  return staging->commit();
}

}  // namespace glarecam
