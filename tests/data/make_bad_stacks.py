#!/usr/bin/env python3
"""Regenerates tests/data/bad-stacks/: one directory per way a stack can be bad.

Each case holds the stack (or what is left of it) and expect.txt: a substring the reader's
one-line error must contain. The corpus is committed; run this only to change it:
    python3 tests/data/make_bad_stacks.py build/bin/glarecam
"""
import binascii
import copy
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "bad-stacks")


def png(width, height, bit_depth, colour_type, raw_rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", binascii.crc32(body) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    data = b"".join(b"\x00" + row for row in raw_rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(data)) +
            chunk(b"IEND", b""))


def main():
    glarecam = sys.argv[1]
    base = tempfile.mkdtemp()
    good = os.path.join(base, "good")
    subprocess.run([glarecam, "simulate", "--out", good, "--size", "32x24", "--alpha", "40", "--fov", "10"],
                   check=True, stdout=subprocess.DEVNULL)
    manifest = json.load(open(os.path.join(good, "stack.json")))
    manifest["frames"] = manifest["frames"][:2]
    frames = [f["file"] for f in manifest["frames"]]
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)

    def case(name, expect, edit=None, files=True, manifest_text=None):
        d = os.path.join(OUT, name)
        os.makedirs(d)
        if files:
            for f in frames:
                shutil.copy(os.path.join(good, f), os.path.join(d, f))
        m = copy.deepcopy(manifest)
        if edit:
            m = edit(m, d) or m
        if manifest_text is not None:
            open(os.path.join(d, "stack.json"), "w").write(manifest_text)
        elif m is not None:
            json.dump(m, open(os.path.join(d, "stack.json"), "w"), indent=2)
        open(os.path.join(d, "expect.txt"), "w").write(expect + "\n")

    def set_path(path, value):
        def edit(m, d):
            target = m
            for key in path[:-1]:
                target = target[key]
            target[path[-1]] = value
        return edit

    def remove_path(path):
        def edit(m, d):
            target = m
            for key in path[:-1]:
                target = target[key]
            del target[path[-1]]
        return edit

    def write_frame(data):
        def edit(m, d):
            open(os.path.join(d, frames[1]), "wb").write(data)
        return edit

    case("missing-manifest", "manifest is missing", edit=lambda m, d: None, files=True, manifest_text=None)
    os.remove(os.path.join(OUT, "missing-manifest", "stack.json"))
    case("invalid-json", "invalid JSON", manifest_text='{"schema": "glarecam.stack/1", "frames": [\n')
    case("manifest-not-object", "must be a JSON object", manifest_text="[1, 2, 3]\n")
    deep = json.dumps(manifest)[:-1] + ', "x": ' + "[" * 100000 + "]" * 100000 + "}"
    case("json-nested-too-deep", "nesting deeper than 64", manifest_text=deep)
    case("wrong-schema", "is not supported", edit=set_path(["schema"], "glarecam.stack/2"))
    case("missing-schema", "schema is missing", edit=remove_path(["schema"]))
    case("empty-frame-list", "frames is empty", edit=set_path(["frames"], []))
    case("frames-not-a-list", "frames must be a list", edit=set_path(["frames"], {"file": "frame-00.png"}))
    case("missing-frame", "frame file is missing", edit=lambda m, d: os.remove(os.path.join(d, frames[1])))
    case("frame-is-directory", "frame file is missing or not a regular file",
         edit=lambda m, d: (os.remove(os.path.join(d, frames[1])), os.mkdir(os.path.join(d, frames[1]))) and None)
    case("zero-byte-png", "frame file is empty", edit=write_frame(b""))
    full = open(os.path.join(good, frames[1]), "rb").read()
    case("truncated-png", "corrupt or truncated PNG", edit=write_frame(full[: len(full) // 2]))
    case("corrupt-png-data", "corrupt or truncated PNG",
         edit=write_frame(full[:60] + bytes(b ^ 0x5A for b in full[60:-12]) + full[-12:]))
    case("not-an-image", "not a PNG or TIFF", edit=write_frame(b"this is not an image\n"))
    case("colour-png", "not a single-channel greyscale PNG",
         edit=write_frame(png(32, 24, 8, 2, [bytes(96)] * 24)))
    case("grey-alpha-png", "not a single-channel greyscale PNG",
         edit=write_frame(png(32, 24, 8, 4, [bytes(64)] * 24)))
    case("4-bit-png", "must be 8- or 16-bit", edit=write_frame(png(32, 24, 4, 0, [bytes(16)] * 24)))
    case("huge-png-header", "too large", edit=write_frame(png(100000, 100000, 16, 0, [])))
    case("png-header-promises-too-much", "far more than the file can hold",
         edit=write_frame(png(8000, 8000, 16, 0, [])))
    case("frame-size-mismatch", "must have the same size",
         edit=write_frame(png(16, 24, 16, 0, [bytes(32)] * 24)))
    case("exposure-zero", "exposure_us must be positive", edit=set_path(["frames", 1, "exposure_us"], 0))
    case("exposure-negative", "exposure_us must be positive", edit=set_path(["frames", 1, "exposure_us"], -5))
    case("exposure-not-a-number", "exposure_us must be a number", edit=set_path(["frames", 1, "exposure_us"], "10us"))
    case("exposure-missing", "frames[1].exposure_us is missing", edit=remove_path(["frames", 1, "exposure_us"]))
    case("exposure-infinite", "number overflow",
         manifest_text=json.dumps(manifest, indent=2).replace(
             '"exposure_us": %s' % json.dumps(manifest["frames"][1]["exposure_us"]), '"exposure_us": 1e999'))
    case("gain-not-a-number", "gain_db must be a number", edit=set_path(["frames", 0, "gain_db"], [3]))
    case("gain-absurd", "outside the range the merge computes in", edit=set_path(["frames", 0, "gain_db"], 1000))
    case("exposure-absurdly-short", "outside the range the merge computes in",
         edit=set_path(["frames", 1, "exposure_us"], 1e-30))
    case("luminance-factor-absurd", "outside the range the merge computes in",
         edit=set_path(["calibration", "luminance_factor"], 1e300))
    case("nd-zero", "nd_transmission must be in (0, 1]", edit=set_path(["frames", 0, "nd_transmission"], 0))
    case("f-number-negative", "f_number must be positive", edit=set_path(["frames", 0, "f_number"], -8))
    case("frame-file-missing-key", "frames[0].file is missing", edit=remove_path(["frames", 0, "file"]))
    case("frame-path-dotdot", "escapes the stack directory", edit=set_path(["frames", 0, "file"], "../good/frame-00.png"))
    case("frame-path-absolute", "escapes the stack directory", edit=set_path(["frames", 0, "file"], "/etc/passwd"))

    def symlink_out(m, d):
        os.remove(os.path.join(d, frames[0]))
        os.symlink("../../../../../../../../etc/hostname", os.path.join(d, frames[0]))
    case("frame-symlink-outside", "links outside the stack directory", edit=symlink_out)
    case("black-at-saturation", "must be below saturation_dn",
         edit=lambda m, d: m["calibration"].update(black_level_dn=4000, saturation_dn=4000))
    case("black-above-saturation", "must be below saturation_dn",
         edit=lambda m, d: m["calibration"].update(black_level_dn=5000))
    case("luminance-factor-negative", "luminance_factor must be positive",
         edit=set_path(["calibration", "luminance_factor"], -1500))
    case("luminance-factor-missing", "calibration.luminance_factor is missing", edit=remove_path(["calibration", "luminance_factor"]))
    case("fx-zero", "intrinsics.fx must be positive", edit=set_path(["calibration", "intrinsics", "fx"], 0))
    case("fy-negative", "intrinsics.fy must be positive", edit=set_path(["calibration", "intrinsics", "fy"], -2400))
    case("cx-not-a-number", "intrinsics.cx must be a number", edit=set_path(["calibration", "intrinsics", "cx"], "centre"))
    case("intrinsics-missing", "calibration.intrinsics is missing", edit=remove_path(["calibration", "intrinsics"]))
    case("distortion-too-long", "at most 5 numbers",
         edit=set_path(["calibration", "intrinsics", "distortion"], [0, 0, 0, 0, 0, 0, 0, 0]))
    case("calibration-path-missing", "calibration file \"../calib/rig1.json\" does not exist",
         edit=set_path(["calibration"], "../calib/rig1.json"))

    def bad_calibration_file(m, d):
        open(os.path.join(d, "calibration.json"), "w").write('{"black_level_dn": 64,,}')
        m["calibration"] = "calibration.json"
    case("calibration-file-invalid-json", "invalid JSON", edit=bad_calibration_file)
    case("no-calibration", "no calibration", edit=remove_path(["calibration"]))
    case("calibration-not-object", "calibration must be an object", edit=set_path(["calibration"], 42))
    case("flat-field-escapes", "escapes the stack directory", edit=set_path(["calibration", "flat_field"], "../flat.exr"))
    case("flat-field-missing", "EXR file is missing", edit=set_path(["calibration", "flat_field"], "flat.exr"))
    case("flat-field-not-exr", "unreadable EXR",
         edit=lambda m, d: (open(os.path.join(d, "flat.exr"), "w").write("not exr"),
                            m["calibration"].update(flat_field="flat.exr")) and None)
    case("alpha-out-of-range", "alpha_deg 120° is outside [0, 90]", edit=set_path(["alpha_deg"], 120))
    case("alpha-not-a-number", "alpha_deg must be a number", edit=set_path(["alpha_deg"], "forty"))
    case("noise-negative", "read_noise_dn must not be negative",
         edit=set_path(["calibration", "noise", "read_noise_dn"], -2))
    shutil.rmtree(base)
    print("wrote", len(os.listdir(OUT)), "cases to", OUT)


if __name__ == "__main__":
    main()
