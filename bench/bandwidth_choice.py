"""Why each sample stands for a band by default (docs/physics.md, "Tabulated inputs on the grid").

The default scene's zenith (six orders) at suns of 30, 2 and -4 degrees, on the default 10 nm grid
and a 5 nm grid, with the solar spectrum and ozone taken as band means (spectrum.bandwidth_nm =
the step) or at the sample wavelength (bandwidth 0), against a 1 nm grid with 1 nm bands. Prints
the luminance's relative difference and the largest difference in CIE xy. About 30 s.

    PYTHONPATH=build/python /usr/bin/python3 bench/bandwidth_choice.py
"""
import numpy as np

import skyspec

ZENITH = {"camera.type": "perspective", "camera.width": 1, "camera.height": 1, "camera.look_at_m": [0, 0, 1000],
          "camera.fov_deg": 1}


def zenith_xyz(sun_elevation_deg, step_nm, bandwidth_nm):
    overrides = dict(ZENITH, **{"sun.elevation_deg": sun_elevation_deg, "spectrum.step_nm": step_nm,
                                "spectrum.bandwidth_nm": bandwidth_nm})
    return skyspec.render(overrides=overrides).xyz[0, 0].astype(float)


def xy(v):
    return v[:2] / v.sum()


for elevation in (30, 2, -4):
    reference = zenith_xyz(elevation, 1, 1)
    for label, step, width in (("10 nm grid, 10 nm bands (default)", 10, 10), ("10 nm grid, point values", 10, 0),
                               ("5 nm grid, 5 nm bands", 5, 5), ("5 nm grid, point values", 5, 0)):
        v = zenith_xyz(elevation, step, width)
        print(f"sun {elevation:3d} deg, {label:34s}: Y {v[1]:9.3f} cd/m2, {100 * (v[1] / reference[1] - 1):+.2f} % "
              f"against 1 nm; xy off by {np.abs(xy(v) - xy(reference)).max():.4f}")
