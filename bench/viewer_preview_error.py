"""How far the viewer's previews are from the exact frames (docs/viewer.md, "Previews").

usage: PYTHONPATH=build/python /usr/bin/python3 bench/viewer_preview_error.py

A preview renders the same scene with the sky-view table at 32 x 16 rows and azimuths, its rays
marched in 32 segments (src/viewer/view_requests.hpp) instead of the scene's 128 x 64 and 64; compared here with the exact render of a
512 x 256 panorama of the upper hemisphere of the default scene at suns 30, 10 and 2 degrees: the
relative error of the spectral radiance, and the 8-bit sRGB code values at the exact frame's
exposure.
"""
import numpy as np

import skyspec

base = {"camera.type": "equirectangular", "camera.width": 512, "camera.height": 256, "camera.min_elevation_deg": 0}


def srgb8(linear):
    x = np.clip(linear, 0, None)
    return np.round(255 * np.clip(np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055), 0, 1))


for elevation in (30, 10, 2):
    scene = dict(base, **{"sun.elevation_deg": elevation})
    exact = skyspec.render(overrides=scene)
    preview = skyspec.render(overrides=dict(scene, **{"render.sky_view_zenith_samples": 32,
                                                      "render.sky_view_azimuth_samples": 16,
                                                      "render.view_segments": 32}))
    rel = np.abs(preview.spectral - exact.spectral) / np.maximum(exact.spectral, 1e-30)
    codes = np.abs(srgb8(exact.rgb * exact.exposure_scale) - srgb8(preview.rgb * exact.exposure_scale))
    print(f"sun {elevation}: radiance relative error median {np.percentile(rel, 50):.2e}, 99th percentile "
          f"{np.percentile(rel, 99):.2e}, max {rel.max():.2e}; 8-bit sRGB: max difference {codes.max():.0f}, "
          f"pixels that differ {np.mean(codes.max(axis=2) > 0) * 100:.1f} %")
