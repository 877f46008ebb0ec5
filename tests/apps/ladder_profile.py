#!/usr/bin/env python3
"""Gives a glare profile without contours (one made from a table such as the paper's Table III)
a contour ladder and a reference illuminance, for the hazard's CLI tests: at every whole degree
with axes, the rungs of a log-quadratic lobe (docs/hazard.md step 7) whose contour at the row's
limit has the row's axes, axis(T) = axis * sqrt(ln(Lmax/T) / ln(Lmax/limit)), for the ladder's
levels (1, 2.15, 4.64 x 10^n from 10 000 cd/m2) below Lmax.

usage: ladder_profile.py IN.json OUT.json [REFERENCE_LX]
"""
import json
import math
import sys

if len(sys.argv) not in (3, 4):
    sys.exit(__doc__)
profile = json.load(open(sys.argv[1]))
reference_lx = float(sys.argv[3]) if len(sys.argv) == 4 else 100000.0
levels = [m * 10.0**n for n in range(4, 9) for m in (1.0, 2.15, 4.64)]
ladder = []
for row in profile["profile"]:
    lmax, limit = row.get("lmax_cd_m2"), row.get("limit_cd_m2")
    v, h = row.get("vertical_deg"), row.get("horizontal_deg")
    if not (lmax and limit and v and h) or lmax <= limit:
        continue
    contours = []
    for level in levels:
        if level >= lmax:
            break
        scale = math.sqrt(math.log(lmax / level) / math.log(lmax / limit))
        cv, ch = v * scale, h * scale
        omega = math.pi / 4 * math.radians(cv) * math.radians(ch)
        contours.append({"level_cd_m2": level, "kind": "ladder", "vertical_deg": cv,
                         "horizontal_deg": ch, "orientation_deg": 0.0, "solid_angle_sr": omega,
                         "uncertainty": {"vertical_deg": 0, "horizontal_deg": 0,
                                         "orientation_deg": 0, "solid_angle_sr": 0}})
    ladder.append({"alpha_deg": row["alpha_deg"], "contours": contours})
profile["schema"] = "glarecam.glare-profile/2"
profile["illuminance"] = {"status": "referred", "reference_lx": reference_lx, "sources": None}
profile["ladder"] = ladder
json.dump(profile, open(sys.argv[2], "w"), indent=1)
