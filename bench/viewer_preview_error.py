"""How far the viewer's previews are from the exact frames (docs/viewer.md, "Previews").

usage: PYTHONPATH=build/python /usr/bin/python3 bench/viewer_preview_error.py

Compared with the exact render of a 512 x 256 panorama of the upper hemisphere at suns 30, 10 and
2 degrees, the default scene and the hazy preset (src/viewer/view_requests.hpp has the settings):

- "coarse sky-view table": the frame while a control moves, the sky-view table at 32 x 16 rows
  and azimuths, its rays marched in 32 segments, instead of the scene's 128 x 64 and 64;
- "small tables": the frame while a new atmosphere's tables are built and the preview's small
  scattering-order tables are at hand (12 x 24 entries, harmonics to degree 6, 4 orders), with
  the coarse sky-view table;
- "single scattering": the frame before either is at hand.

For each, the relative error of the spectral radiance and the 8-bit sRGB code values at the exact
frame's exposure.
"""
import numpy as np

import skyspec

base = {"camera.type": "equirectangular", "camera.width": 512, "camera.height": 256, "camera.min_elevation_deg": 0}
coarse = {"render.sky_view_zenith_samples": 32, "render.sky_view_azimuth_samples": 16, "render.view_segments": 32}
small_tables = dict(coarse, **{"render.ms_altitude_samples": 12, "render.ms_sun_samples": 24,
                               "render.ms_angular_degree": 6, "render.scattering_orders": 4})
single = dict(coarse, **{"render.scattering_orders": 1})


def srgb8(linear):
    x = np.clip(linear, 0, None)
    return np.round(255 * np.clip(np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055), 0, 1))


for preset in ("default", "hazy"):
    for elevation in (30, 10, 2):
        scene = dict(base, **{"sun.elevation_deg": elevation})
        exact = skyspec.render(preset=preset, overrides=scene)
        for name, keys in (("coarse sky-view table", coarse), ("small tables", small_tables),
                           ("single scattering", single)):
            preview = skyspec.render(preset=preset, overrides=dict(scene, **keys))
            rel = np.abs(preview.spectral - exact.spectral) / np.maximum(exact.spectral, 1e-30)
            codes = np.abs(srgb8(exact.rgb * exact.exposure_scale) - srgb8(preview.rgb * exact.exposure_scale))
            print(f"{preset}, sun {elevation}, {name}: radiance relative error median {np.percentile(rel, 50):.2e}, "
                  f"99th percentile {np.percentile(rel, 99):.2e}, max {rel.max():.2e}; 8-bit sRGB: max difference "
                  f"{codes.max():.0f}, pixels that differ {np.mean(codes.max(axis=2) > 0) * 100:.1f} %", flush=True)
