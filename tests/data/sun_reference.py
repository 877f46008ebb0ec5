#!/usr/bin/env python3
"""Reference sun positions for tests/capture/solar_position_test.cpp, from astropy.

Run offline (Debian's python3-astropy 5.2.1, bundled IERS tables, astropy's built-in ERFA
ephemeris): /usr/bin/python3 tests/data/sun_reference.py. It prints one C++ initializer per case:
the topocentric apparent position without refraction (AltAz with pressure=0 at the site's height)
and the UT1 - UTC and TT - UT1 that astropy used, which the test passes to solarPosition() so that
both compute the same instant. Beyond the bundled IERS table (dates after about 2023) astropy
warns and holds its last UT1 - UTC (-0.0192 s), so the future cases compare the algorithms, not a
prediction of UT1. Not run in CI (no python there).
"""
import warnings

import astropy.units as u
from astropy.coordinates import AltAz, EarthLocation, get_sun, solar_system_ephemeris
from astropy.time import Time
from astropy.utils import iers

iers.conf.auto_download = False
iers.conf.iers_degraded_accuracy = "warn"
warnings.simplefilter("ignore")

# name, UTC, latitude, longitude, height (m)
CASES = [
    ("NREL example, Golden CO", "2003-10-17T19:30:30", 39.742476, -105.1786, 1830.14),
    ("Sydney, southern summer", "2024-12-21T02:00:00", -33.8688, 151.2093, 50.0),
    ("Tromso, midnight sun before north", "2025-06-21T22:30:00", 69.6492, 18.9553, 10.0),
    ("Tromso, midnight sun after north", "2025-06-21T23:00:00", 69.6492, 18.9553, 10.0),
    ("Freiburg, just after sunrise", "2026-03-20T05:35:00", 47.9990, 7.8421, 278.0),
    ("Freiburg, winter noon 2026", "2026-11-26T11:30:00", 47.9990, 7.8421, 278.0),
    ("McMurdo, polar day", "2026-01-15T12:00:00", -77.8463, 166.6683, 24.0),
    ("Quito, high and equatorial", "2025-03-20T17:10:00", -0.1807, -78.4678, 2850.0),
    ("Cape Town, afternoon", "2019-02-03T14:45:12.5", -33.9249, 18.4241, 15.0),
]

with solar_system_ephemeris.set("builtin"):
    for name, utc, lat, lon, height in CASES:
        t = Time(utc, scale="utc")
        site = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, height * u.m)
        altaz = get_sun(t).transform_to(AltAz(obstime=t, location=site, pressure=0 * u.hPa))
        dut1 = (t.ut1.jd1 - t.utc.jd1 + t.ut1.jd2 - t.utc.jd2) * 86400
        dt = (t.tt.jd1 - t.ut1.jd1 + t.tt.jd2 - t.ut1.jd2) * 86400
        print(f'    {{"{name}", "{utc}Z", {lat}, {lon}, {height}, {dut1:.4f}, {dt:.4f}, '
              f'{altaz.alt.deg:.6f}, {altaz.az.deg:.6f}}},')
