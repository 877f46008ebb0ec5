#!/usr/bin/env python3
"""scripts/make-city: the same seed gives the same bytes, another seed other bytes; the features'
kinds and counts; every array a planar, simple rectangle whose Newell normal points up (or out of
its facade) and toward its azimuth, above its roof; every window outside its building facing out;
the receptors counted as the hazard samples them; --help and bad usage (exit 2).

    tests/scripts/make_city_test.py [MAKE_CITY]

The geometry is checked in the east-north-up frame at the ground below the first array's first vertex from WGS84
geodetic coordinates through ECEF (what the reader's PROJ topocentric conversion does), not
through the generator's own conversion.
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
MAKE_CITY = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "scripts", "make-city")
A, F = 6378137.0, 1 / 298.257223563
E2 = F * (2 - F)
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        if len(failures) <= 20:
            print(f"FAIL: {what}", file=sys.stderr)


def run(*args):
    return subprocess.run([sys.executable, MAKE_CITY, *args], capture_output=True, text=True)


def ecef(lon, lat, h):
    lam, phi = math.radians(lon), math.radians(lat)
    n = A / math.sqrt(1 - E2 * math.sin(phi) ** 2)
    return ((n + h) * math.cos(phi) * math.cos(lam), (n + h) * math.cos(phi) * math.sin(lam),
            (n * (1 - E2) + h) * math.sin(phi))


class Topocentric:
    def __init__(self, lon, lat, h):
        self.origin = ecef(lon, lat, h)
        lam, phi = math.radians(lon), math.radians(lat)
        self.e = (-math.sin(lam), math.cos(lam), 0.0)
        self.n = (-math.sin(phi) * math.cos(lam), -math.sin(phi) * math.sin(lam), math.cos(phi))
        self.u = (math.cos(phi) * math.cos(lam), math.cos(phi) * math.sin(lam), math.sin(phi))

    def __call__(self, position, ground_m):
        p = ecef(position[0], position[1], position[2] + ground_m)
        d = [p[i] - self.origin[i] for i in range(3)]
        return tuple(sum(d[i] * axis[i] for i in range(3)) for axis in (self.e, self.n, self.u))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def newell(points):
    n = [0.0, 0.0, 0.0]
    for i, p in enumerate(points):
        q = points[(i + 1) % len(points)]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return tuple(n)


def inside_2d(point, polygon):
    inside = False
    for i, p in enumerate(polygon):
        q = polygon[i - 1]
        if (p[1] > point[1]) != (q[1] > point[1]):
            x = p[0] + (point[1] - p[1]) * (q[0] - p[0]) / (q[1] - p[1])
            if x > point[0]:
                inside = not inside
    return inside


def distance_to_polygon_2d(point, polygon):
    best = math.inf
    for i, p in enumerate(polygon):
        q = polygon[i - 1]
        d = (q[0] - p[0], q[1] - p[1])
        t = max(0.0, min(1.0, ((point[0] - p[0]) * d[0] + (point[1] - p[1]) * d[1]) /
                         (d[0] ** 2 + d[1] ** 2)))
        best = min(best, math.hypot(point[0] - p[0] - t * d[0], point[1] - p[1] - t * d[1]))
    return best


def azimuth(v):
    return math.degrees(math.atan2(v[0], v[1])) % 360


def angle_between_deg(a, b):
    return abs((a - b + 180) % 360 - 180)


def route_samples(length, spacing):
    """hazard/scene.cpp: every spacing from the start, and the end when it lies apart."""
    whole = math.floor(length / spacing)
    return int(whole) + 1 + (1 if length - whole * spacing > 1e-6 else 0)


def area_samples(points, spacing):
    """hazard/scene.cpp: cell centres of a grid aligned with the polygon's bounding box in its
    plane (a level polygon: east and north), those inside; the centroid when none is."""
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    columns = max(1, math.ceil((max(xs) - min(xs)) / spacing - 1e-9))
    rows = max(1, math.ceil((max(ys) - min(ys)) / spacing - 1e-9))
    x0 = (min(xs) + max(xs)) / 2 - (columns - 1) * spacing / 2
    y0 = (min(ys) + max(ys)) / 2 - (rows - 1) * spacing / 2
    count = sum(inside_2d((x0 + c * spacing, y0 + r * spacing), points)
                for r in range(rows) for c in range(columns))
    return max(count, 1)


def check_scene(path, roofs, receptors, roads):
    with open(path, encoding="utf-8") as f:
        scene = json.load(f)
    meta = scene.get("glarecam", {})
    check(scene.get("type") == "FeatureCollection", "not a FeatureCollection")
    check(meta.get("schema") == "glarecam.hazard-geo/1", f"schema {meta.get('schema')}")
    check(meta.get("vertical_reference") == "ground" and meta.get("ground_elevation_m") == 410
          and meta.get("utc_offset_h") == 1.0, f"glarecam member {meta}")
    ground = meta["ground_elevation_m"]
    allowed = {"array": set(), "observer": {"facing_azimuth_deg"},
               "route": {"direction", "spacing_m", "field_of_view_deg"},
               "area": {"eye_height_m", "spacing_m", "hours"}, "obstruction": {"base_m", "height_m"}}
    geometry = {"array": "Polygon", "observer": "Point", "route": "LineString", "area": "Polygon",
                "obstruction": "Polygon"}
    by_kind = {kind: [] for kind in allowed}
    names = set()
    for feature in scene["features"]:
        props = feature["properties"]
        kind = props.get("kind")
        check(kind in allowed, f"kind {kind}")
        check(set(props) - {"kind", "name"} <= allowed.get(kind, set()),
              f"{props.get('name')}: keys {sorted(props)}")
        check(feature["geometry"]["type"] == geometry.get(kind), f"{props.get('name')}: geometry")
        check(props["name"] not in names, f"name {props['name']} twice")
        names.add(props["name"])
        if feature["geometry"]["type"] == "Polygon":
            ring = feature["geometry"]["coordinates"][0]
            check(ring[0] == ring[-1] and len(ring) >= 4, f"{props['name']}: ring not closed")
        by_kind[kind].append(feature)
    check(len(by_kind["array"]) == roofs, f"{len(by_kind['array'])} arrays, not {roofs}")
    check(len(by_kind["obstruction"]) == roofs, f"{len(by_kind['obstruction'])} obstructions")
    check(len(by_kind["route"]) == roads, f"{len(by_kind['route'])} routes, not {roads}")
    check(len(by_kind["observer"]) > receptors / 2, "the receptors are not mostly windows")

    first = by_kind["array"][0]["geometry"]["coordinates"][0][0]
    # The site at the ground below the first array's first vertex: z is the height above the
    # ground there (less the earth's curvature away from it).
    enu = Topocentric(first[0], first[1], ground)
    buildings = {}
    for feature in by_kind["obstruction"]:
        props = feature["properties"]
        # Each building in its own frame too (at its first corner): the earth's curvature turns
        # local up away from the site's, by 0.3 mrad 2 km away, a centimetre at a window's height.
        lonlat = feature["geometry"]["coordinates"][0]
        local = Topocentric(lonlat[0][0], lonlat[0][1], ground)
        footprint = [local(p, ground) for p in lonlat[:-1]]
        check(props["base_m"] == 0 and props["height_m"] > 0, f"{props['name']}: base, height")
        check(newell(footprint)[2] > 0, f"{props['name']}: footprint clockwise")
        buildings[props["name"].split("-")[1]] = (footprint, props["height_m"], local)

    tilts = []
    for feature in by_kind["array"]:
        name = feature["properties"]["name"]
        corners = [enu(p, ground) for p in feature["geometry"]["coordinates"][0][:-1]]
        normal = newell(corners)
        n = tuple(x / norm(normal) for x in normal)
        centre = tuple(sum(c[i] for c in corners) / len(corners) for i in range(3))
        check(all(abs(dot(sub(c, centre), n)) < 0.01 for c in corners), f"{name}: not planar")
        sides = [sub(corners[(i + 1) % 4], corners[i]) for i in range(4)]
        check(all(abs(dot(sides[i], sides[(i + 1) % 4])) < 1e-3 * norm(sides[i]) *
                  norm(sides[(i + 1) % 4]) for i in range(4)), f"{name}: not a rectangle")
        check(n[2] > 0, f"{name}: faces down ({n[2]:.2e})")
        tilt = math.degrees(math.acos(max(-1.0, min(1.0, n[2]))))
        tilts.append(tilt)
        footprint, height, local = buildings[name.split("-")[1]]
        # Local up differs from the site's by the distance over the earth's radius: tilt within.
        slack_deg = math.degrees(math.hypot(centre[0], centre[1]) / 6.37e6) + 0.01
        # Above the roof by at least 0.1 m on a reader that extrudes each footprint from the
        # site's level plane (z = 0 there) too.
        if tilt < 89:
            check(tilt <= 60 + slack_deg, f"{name}: tilt {tilt:.2f}")
            check(all(c[2] >= height + 0.1 - 1e-3 for c in corners),
                  f"{name}: inside a roof extruded from the site's z = 0")
        corners = [local(p, ground) for p in feature["geometry"]["coordinates"][0][:-1]]
        if tilt < 89:
            for c in corners:
                check(inside_2d(c, footprint), f"{name}: off its roof")
                check(c[2] >= height + 0.1, f"{name}: {c[2] - height:.3f} m above its roof")
        else:
            check(tilt <= 90 + slack_deg, f"{name}: tilt {tilt:.2f}")
            for c in corners:
                check(not inside_2d(c, footprint) and distance_to_polygon_2d(c, footprint) > 0.15,
                      f"{name}: vertical array not outside its facade")
    check(any(t < 0.5 for t in tilts), "no level array")
    check(any(t > 89 for t in tilts), "no vertical array")
    check(any(30 < t < 61 for t in tilts), "no array tilted 30-60 deg")
    azimuths = [azimuth(newell([enu(p, ground) for p in f["geometry"]["coordinates"][0][:-1]]))
                for f, t in zip(by_kind["array"], tilts) if t > 1]
    for quadrant in range(4):
        check(any(quadrant * 90 <= a < quadrant * 90 + 90 for a in azimuths),
              f"no array faces {quadrant * 90}-{quadrant * 90 + 90} deg")

    for feature in by_kind["observer"]:
        name = feature["properties"]["name"]
        footprint, height, local = buildings[name.split("-")[1]]
        p = local(feature["geometry"]["coordinates"], ground)
        check(not inside_2d(p, footprint), f"{name}: inside its building")
        check(abs(distance_to_polygon_2d(p, footprint) - 0.3) < 0.01,
              f"{name}: {distance_to_polygon_2d(p, footprint):.3f} m from its facade")
        check(0 < feature["geometry"]["coordinates"][2] < height, f"{name}: height")
        # Facing out: a step toward the facing direction goes away from the building.
        a = math.radians(feature["properties"]["facing_azimuth_deg"])
        ahead = (p[0] + math.sin(a), p[1] + math.cos(a))
        check(distance_to_polygon_2d(ahead, footprint) > 1.2, f"{name}: does not face out")

    points = len(by_kind["observer"])
    for feature in by_kind["area"]:
        corners = [enu(p, ground) for p in feature["geometry"]["coordinates"][0][:-1]]
        points += area_samples(corners, feature["properties"]["spacing_m"])
    for feature in by_kind["route"]:
        ends = [enu(p, ground) for p in feature["geometry"]["coordinates"]]
        length = sum(norm(sub(ends[i + 1], ends[i])) for i in range(len(ends) - 1))
        points += route_samples(length, feature["properties"]["spacing_m"])
    check(points == receptors, f"{points} receptor points, not {receptors}")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        first, second, other = (os.path.join(tmp, name) for name in ("a.geojson", "b.geojson", "c.geojson"))
        args = ["--roofs", "300", "--receptors", "2000", "--roads", "3", "--seed", "7"]
        for out in (first, second):
            result = run(*args, "--out", out)
            check(result.returncode == 0, f"make-city {args}: exit {result.returncode}: {result.stderr}")
        with open(first, "rb") as a, open(second, "rb") as b:
            check(a.read() == b.read(), "the same seed gave different bytes")
        stdout = run(*args)
        with open(first, encoding="ascii") as a:
            check(stdout.stdout == a.read(), "stdout differs from --out")
        run("--roofs", "300", "--receptors", "2000", "--roads", "3", "--seed", "8", "--out", other)
        with open(first, "rb") as a, open(other, "rb") as c:
            check(a.read() != c.read(), "another seed gave the same bytes")
        check_scene(first, 300, 2000, 3)
        # Far from the equator and the meridian, no roads, a receptor count a terrace does not fill.
        result = run("--roofs", "37", "--receptors", "203", "--roads", "0", "--origin=-122.3,60.1", "--out", other)
        check(result.returncode == 0, f"--roads 0: exit {result.returncode}: {result.stderr}")
        check_scene(other, 37, 203, 0)
        # The district's size, quickly.
        start = time.monotonic()
        result = run("--roofs", "5000", "--receptors", "20000", "--out", other)
        seconds = time.monotonic() - start
        check(result.returncode == 0, f"5000 x 20000: exit {result.returncode}")
        check(seconds < 60, f"5000 roofs x 20000 receptors took {seconds:.1f} s")
        print(f"make-city: 5000 roofs x 20000 receptors in {seconds:.1f} s: {result.stderr.strip()}")
        check_scene(other, 5000, 20000, 2)

    help_run = run("--help")
    check(help_run.returncode == 0 and "--receptors" in help_run.stdout, "--help")
    for bad in (["--receptors", "10"], ["--roofs", "0", "--receptors", "10"],
                ["--roofs", "5", "--receptors", "-1"], ["--roofs", "x", "--receptors", "1"],
                ["--roofs", "5", "--receptors", "10", "--origin", "8.5"],
                ["--roofs", "5", "--receptors", "10", "--origin", "200,10"],
                ["--roofs", "5", "--receptors", "3", "--roads", "2"],
                ["--roofs", "1", "--receptors", "100000"], ["--roofs", "5", "--bogus"]):
        result = run(*bad)
        check(result.returncode == 2 and result.stdout == "",
              f"{bad}: exit {result.returncode}, expected 2")

    if failures:
        print(f"0 passed, {len(failures)} failed", file=sys.stderr)
        return 1
    print("make-city: same bytes for the same seed; kinds, counts and geometry as documented")
    return 0


if __name__ == "__main__":
    sys.exit(main())
