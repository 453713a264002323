"""Could the higher orders be built at fewer wavelengths and interpolated? What that would err.

usage: spectral_higher_orders.py SKYSPEC [--out DIR] [--size N]

The scattering-order tables cost in proportion to their wavelengths. This measures how smooth
the higher orders' light is across the spectrum, from renders alone: for the default and hazy
presets at suns 30, 5 and -4 degrees (and the same without ozone) it renders a fisheye (N x N,
default 96; 41 wavelengths, 380-780 nm; a flat sun spectrum, so that the Fraunhofer lines do not
count) with all orders and with single scattering alone; their difference is the higher orders'
radiance H. H is then kept at every 2nd or 3rd wavelength (and the last) and interpolated back
at the others, linearly in wavelength and by cubics in (ln wavelength, ln H); the error, relative
to the whole sky's radiance at that pixel and wavelength, over the lit pixels and the left-out
wavelengths: median / 99th percentile / largest, in per cent, and the wavelength of the largest.
This interpolates the radiance at the camera, which includes the view path's ozone; tables
interpolated in wavelength would keep that exact but not the ozone on the light's way to each
node. docs/performance.md quotes it. Tables are cached in DIR/cache (under a minute from empty on 2 cores).
"""

import argparse
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from bench_stats import read_exr  # this folder's: the spectral channels S0.* of a skyspec EXR

SCENES = [("default", 30), ("default", 5), ("default", -4), ("hazy", 10), ("hazy", -4)]


def interpolate(h, wl, kept, method):
    """h at every wavelength from its values at `kept` (indices), by `method`."""
    cubic = method == "log-log cubic"
    x = np.log(wl) if cubic else wl
    y = np.log(np.maximum(h[..., kept], 1e-30)) if cubic else h[..., kept]
    xk = x[kept]
    out = np.empty_like(h)
    for i in range(len(wl)):
        j = min(max(int(np.searchsorted(xk, x[i])), 1), len(xk) - 1)
        if cubic and 2 <= j <= len(xk) - 2:  # Lagrange through the four nodes around
            nodes = range(j - 2, j + 2)
            v = 0.0
            for a in nodes:
                w = np.prod([(x[i] - xk[b]) / (xk[a] - xk[b]) for b in nodes if b != a])
                v = v + w * y[..., a]
        else:
            t = (x[i] - xk[j - 1]) / (xk[j] - xk[j - 1])
            v = (1 - t) * y[..., j - 1] + t * y[..., j]
        out[..., i] = np.exp(v) if cubic else v
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("skyspec")
    ap.add_argument("--out", default="/tmp/skyspec-spectral-higher")
    ap.add_argument("--size", type=int, default=96)
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, SKYSPEC_CACHE_DIR=str(out / "cache"))
    presets = Path(__file__).resolve().parent.parent / "data" / "scenes"
    print("kept | interpolation | " + " | ".join(f"{p} sun {s}" for p, s in SCENES))
    for ozone in (True, False):
        rows = {}
        for preset, sun in SCENES:
            imgs = []
            for orders in (6, 1):
                name = f"{preset}{sun}{'' if ozone else '-noozone'}-orders{orders}"
                subprocess.run([a.skyspec, "render", "-q", "--no-png", "--out", str(out), "--name", name,
                                "--scene", str(presets / f"{preset}.toml"), "--sun-elevation", str(sun),
                                "--width", str(a.size), "--height", str(a.size), "--set", "sun.spectrum=flat",
                                "--set", f"atmosphere.ozone.enabled={'true' if ozone else 'false'}",
                                "--set", f"render.scattering_orders={orders}"], check=True, env=env)
                imgs.append(read_exr(out / f"{name}.exr"))
            (total, wl), (single, _) = imgs
            wl = np.asarray(wl)
            h = total - single
            lit = total.max(axis=-1) > 1e-6 * total.max()
            for step in (2, 3):
                kept = list(range(0, len(wl), step))
                if kept[-1] != len(wl) - 1:
                    kept.append(len(wl) - 1)
                left = [i for i in range(len(wl)) if i not in kept]
                for method in ("linear", "log-log cubic"):
                    with np.errstate(divide="ignore", invalid="ignore"):  # a dark wavelength: no error counted
                        err = np.where(total > 0, np.abs(interpolate(h, wl, kept, method) - h) / total, 0.0)
                    err = err[lit][:, left]
                    worst = wl[left][int(np.argmax(err.max(axis=0)))]
                    rows.setdefault((step, len(kept), method), []).append(
                        f"{100 * np.median(err):.3f} / {100 * np.percentile(err, 99):.2f} / {100 * err.max():.2f} "
                        f"({worst:.0f} nm)")
        print(f"with ozone: {'yes' if ozone else 'no'}")
        for (step, n, method), cells in rows.items():
            print(f"every {('2nd', '3rd')[step - 2]} ({n} wavelengths) | {method} | " + " | ".join(cells))
    return 0


if __name__ == "__main__":
    sys.exit(main())
