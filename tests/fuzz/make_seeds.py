#!/usr/bin/env python3
"""Regenerates tests/fuzz/seeds/: the valid inputs each fuzz target starts from.

scripts/fuzz adds the project's other files of each kind (the bad-stack corpus, the shipped
config and GenICam presets, the example hazard scene) and tests/fuzz/regressions/<target>/.
The seeds are committed; run this only to change them, from a finished `make demo`:
    python3 tests/fuzz/make_seeds.py demo-out
"""
import json
import math
import os
import shutil
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = os.path.join(HERE, "seeds")
BAD_STACKS = os.path.join(HERE, "..", "data", "bad-stacks")


def tiff16(width, height, compression):
    """A little-endian single-strip 16-bit greyscale TIFF: 1 none, 8 Adobe deflate."""
    pixels = b"".join(struct.pack("<H", 64 + 37 * x + 11 * y) for y in range(height) for x in range(width))
    strip = zlib.compress(pixels) if compression == 8 else pixels
    entries = [(256, 3, 1, width), (257, 3, 1, height), (258, 3, 1, 16), (259, 3, 1, compression),
               (262, 3, 1, 1), (273, 4, 1, 0), (277, 3, 1, 1), (278, 3, 1, height),
               (279, 4, 1, len(strip))]
    ifd_offset = 8
    strip_offset = ifd_offset + 2 + 12 * len(entries) + 4
    out = b"II*\x00" + struct.pack("<I", ifd_offset) + struct.pack("<H", len(entries))
    for tag, kind, count, value in entries:
        if tag == 273:
            value = strip_offset
        packed = struct.pack("<H", value) + b"\x00\x00" if kind == 3 else struct.pack("<I", value)
        out += struct.pack("<HHI", tag, kind, count) + packed
    return out + struct.pack("<I", 0) + strip


def put(target, name, data):
    os.makedirs(os.path.join(SEEDS, target), exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(SEEDS, target, name), mode) as f:
        f.write(data)


def epw_seeds():
    """The epw target's: the real-format fixture (a header as climate.onebuilding.org writes it and
    two days of records: it ends early), and a whole year with only the fields glarecam reads
    (blank fields are the format's own), which parses, so the round trip and the interpolation
    are reached."""
    fixture = os.path.join(HERE, "..", "data", "weather", "freiburg-two-days.epw")
    put("epw", "freiburg-two-days.epw", open(fixture, "rb").read())
    lines = ["LOCATION,Sparse.Year,-,-,glarecam seed,000000,48.0,7.8,1,250", "DESIGN CONDITIONS,0",
             "TYPICAL/EXTREME PERIODS,0", "GROUND TEMPERATURES,0", "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0",
             "COMMENTS 1,", "COMMENTS 2,", "DATA PERIODS,1,1,Data,Monday, 1/ 1,12/31"]
    days = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31]
    for month, count in enumerate(days, start=1):
        for day in range(1, count + 1):
            for hour in range(1, 25):
                lx = max(0, round(90000 * math.sin(math.pi * (hour - 6.5) / 13))) if 7 <= hour <= 19 else 0
                lines.append(f"2001,{month},{day},{hour},0" + "," * 13 + str(lx) + "," * 12)
    put("epw", "year-sparse.epw", "\n".join(lines) + "\n")


def main():
    demo = sys.argv[1]
    shutil.rmtree(SEEDS, ignore_errors=True)
    # A valid manifest for the stack target's two frames (the bad-stack corpus's, made good).
    manifest = json.load(open(os.path.join(BAD_STACKS, "exposure-zero", "stack.json")))
    manifest["frames"][1]["exposure_us"] = 12458.0
    put("stack", "good.json", json.dumps(manifest, indent=2) + "\n")
    put("frame", "none.tiff", tiff16(8, 4, 1))
    put("frame", "deflate.tiff", tiff16(8, 4, 8))
    shutil.copy(os.path.join(BAD_STACKS, "exposure-zero", "frame-00.png"), os.path.join(SEEDS, "frame", "good.png"))
    put("calibration", "rig.json", open(os.path.join(demo, "rig", "calibration.json")).read())
    put("zero_offset", "rig.json", open(os.path.join(demo, "rig", "calibration.json")).read())
    put("sweep", "sweep.csv", open(os.path.join(demo, "sweep", "sweep.csv")).read())
    for alpha in ("05", "60", "80"):
        put("result", f"alpha-{alpha}.json",
            open(os.path.join(demo, "sweep", "results", f"alpha-{alpha}", "result.json")).read())
    put("config", "rig.toml", open(os.path.join(demo, "rig", "rig.toml")).read())
    put("config", "simulated.toml", open(os.path.join(demo, "daemon", "glarecamd-simulated.toml")).read())
    put("glare_profile", "profile.json", open(os.path.join(demo, "sweep", "glare-profile.json")).read())
    scene = json.load(open(os.path.join(HERE, "..", "..", "docs", "examples", "hazard-scene.json")))
    for array in scene.get("arrays", []):
        array["profile"] = "profile.json"  # the hazard_scene target's scratch profile
    put("hazard_scene", "with-profile.json", json.dumps(scene, indent=2) + "\n")
    for name, uri in [("sim", "sim:alpha=40,size=64x48,seed=2"), ("aravis", "aravis:192.168.1.20"),
                      ("inclinometer", "30,roll_deg=1,offset_x_deg=0.3,noise_g=0.0001,seed=2,fault=saturated")]:
        put("uri", name + ".txt", uri)
    epw_seeds()


if __name__ == "__main__":
    main()
