// Reading and writing recorded stacks (docs/stack-format.md).
// readStack() resolves the calibration (command-line file > manifest path > inline block),
// decodes every frame (in parallel) and the calibration's images (flat field, dark frame, hot
// pixels; each must have the frames' size), and checks the whole stack; the first
// problem is returned as a kBadInput Error naming the file. writeStack() builds the stack in a
// hidden sibling directory and renames it into place, so readers never see half a stack.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam {

inline constexpr std::string_view kNoCalibration = "none";

struct Stack {
  std::filesystem::path directory;
  StackManifest manifest;
  Calibration calibration;         // the one in force, after overrides
  std::string calibration_origin;  // "inline", the manifest's path, or the --calibration file
  std::vector<RawFrame> frames;    // in manifest order
  std::vector<int> bit_depths;     // of each frame's file
  std::optional<FloatImage> flat_field;
  std::optional<FloatImage> dark_frame_dn;  // the calibration's dark frame, in DN
  std::optional<ByteImage> hot_pixels;      // non-zero where hot
};

struct StackReadOptions {
  std::optional<std::filesystem::path> calibration_file;  // overrides the manifest's
  bool decode_frames = true;                              // false: manifest and calibration only
  // false: a stack without any calibration is read (calibration targets: the procedures make
  // it); `calibration` is then all zeros and calibration_origin is kNoCalibration.
  bool require_calibration = true;
  unsigned threads = 0;  // 0: all cores
};

Result<Stack> readStack(const std::filesystem::path& directory,
                        const StackReadOptions& options = {});

// Reads a calibration file: a JSON object with the keys of the manifest's calibration block
// (glarecam.calibration/1 is a superset).
Result<Calibration> readCalibrationFile(const std::filesystem::path& path);

struct StackAttachment {
  std::string relative_path;     // where it goes inside the stack
  std::filesystem::path source;  // the file to copy
};

struct StackWriteRequest {
  StackManifest manifest;  // frames[i].file names frames[i]'s file
  std::span<const RawFrame> frames;
  int bit_depth = 16;                                           // 16 or 8
  std::vector<StackAttachment> attachments;                     // e.g. the flat field
  std::vector<std::pair<std::string, std::string>> text_files;  // relative path, content
  bool may_replace = true;  // false: an existing stack at the path (even one written meanwhile by
                            // another process) is left alone and the write fails
};

// Writes the stack at `directory`, or atomically replaces the stack that is there. Anything else
// at that path (a file, a directory without stack.json, "/", ".") is refused as kBadInput:
// replacing deletes the old contents, and those must only ever be an older stack.
Status writeStack(const std::filesystem::path& directory, const StackWriteRequest& request);

// True for a directory holding a stack.json of schema glarecam.stack/1.
bool isStackDirectory(const std::filesystem::path& directory);

// The absolute, normalised path a stack at `requested` would be written to, or the reason it
// cannot be (see writeStack).
Result<std::filesystem::path> stackTarget(const std::filesystem::path& requested);

}  // namespace glarecam
