"""What the sky-view table's coarser table of the higher orders errs (render.sky_view_higher_*).

usage: sky_view_higher.py SKYSPEC [--out DIR] [--size WxH] [--coarse 32x64,32x32]

For the default and hazy presets at suns 30, 10, 2 and -4 degrees renders a whole-sphere
equirectangular panorama (256 x 128, 41 wavelengths, tables cached as usual) with the higher
orders on the table's own rays (render.sky_view_higher_* = the table's 128 x 64), with each
coarser table asked for, and with every pixel marched (render.sky_view_table = false); prints per
render the relative difference of the spectral radiance against the table's own rays (per pixel the
largest over the wavelengths: median / 99th percentile / largest, in per cent), and the table's own
against marching for scale. Then the time of each table, from the renders' own split ("tables",
which includes reading the scattering-order tables from the cache). docs/physics.md quotes it.
"""

import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_stats import read_exr  # this folder's: the spectral channels S0.* of a skyspec EXR

TABLES = re.compile(r"\(tables ([0-9.]+) s")


def differences(img, ref):
    peak = ref.max(axis=-1)
    mask = peak > 1e-6 * peak.max()
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(ref > 0, np.abs(img - ref) / np.abs(ref), np.where(img == ref, 0.0, np.inf)).max(axis=-1)[mask]
    return 100 * np.percentile(rel, 50), 100 * np.percentile(rel, 99), 100 * rel.max()


def render(skyspec, out, name, preset, sun, size, keys):
    w, h = size
    cmd = [skyspec, "render", "--no-png", "--preset", preset, "--out", str(out), "--name", name, "--camera",
           "equirectangular", "--width", str(w), "--height", str(h), "--sun-elevation", str(sun)]
    for k, v in keys.items():
        cmd += ["--set", f"{k}={v}"]
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    m = TABLES.search(p.stdout)
    return read_exr(out / f"{name}.exr")[0], float(m.group(1)) if m else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("skyspec")
    ap.add_argument("--out", help="folder for the renders (default: a temporary one)")
    ap.add_argument("--size", default="256x128")
    ap.add_argument("--coarse", default="32x64,32x32", help="coarser tables, rows x columns, comma-separated")
    a = ap.parse_args()
    out = Path(a.out or tempfile.mkdtemp(prefix="skyspec-sky-view-higher-"))
    out.mkdir(parents=True, exist_ok=True)
    size = tuple(int(v) for v in a.size.split("x"))
    coarse = [tuple(int(v) for v in c.split("x")) for c in a.coarse.split(",")]
    own = {"render.sky_view_higher_zenith_samples": 128, "render.sky_view_higher_azimuth_samples": 64}
    print(f"sky-view table 128 x 64, {size[0]} x {size[1]} whole-sphere panoramas, 41 wavelengths; relative "
          "difference per pixel (largest over the wavelengths), median / p99 / largest, per cent")
    print("| preset | sun (deg) | table vs marching every pixel | " +
          " | ".join(f"higher orders from {r} x {c}" for r, c in coarse) + " |")
    print("| --- | ---: | --- | " + " | ".join("---" for _ in coarse) + " |")
    seconds = {c: [] for c in [(128, 64)] + coarse}
    for preset in ("default", "hazy"):
        for sun in (30, 10, 2, -4):
            ref, t = render(a.skyspec, out, f"{preset}{sun}-own", preset, sun, size, own)
            if sun != 30:  # the first sun's render builds the scattering-order tables
                seconds[(128, 64)].append(t)
            marched, _ = render(a.skyspec, out, f"{preset}{sun}-marched", preset, sun, size,
                                {"render.sky_view_table": "false"})
            cells = ["%.3f / %.3f / %.3f" % differences(ref, marched)]
            for r, c in coarse:
                img, t = render(a.skyspec, out, f"{preset}{sun}-{r}x{c}", preset, sun, size,
                                {"render.sky_view_higher_zenith_samples": r,
                                 "render.sky_view_higher_azimuth_samples": c})
                seconds[(r, c)].append(t)
                cells.append("%.3f / %.3f / %.3f" % differences(img, ref))
            print(f"| {preset} | {sun} | " + " | ".join(cells) + " |")
            sys.stdout.flush()
    print("the renders' \"tables\" (the sky-view table and reading the scattering-order tables), median over the "
          "renders with the tables cached: " +
          ", ".join(f"{r} x {c}: {np.median(v):.3f} s" for (r, c), v in seconds.items()))


if __name__ == "__main__":
    main()
