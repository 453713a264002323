"""What interpolated tables err (render.ms_tables = "interpolated", src/render/table_family.hpp).

For random atmospheres of the default scene (aerosol amount, Angstrom exponent and ozone column
drawn uniformly, seeded), renders the same panorama with exact tables (built for that atmosphere)
and with interpolated ones (blended from the grid's atmospheres), at several suns, and prints per
sky and sun the per-pixel relative difference (the largest over the wavelengths; pixels above 1e-6
of the image's peak): median, 99th percentile and largest. Each render has its own empty table
cache for the exact tables, and one shared cache for the grid's (the first sky builds most of them).
Not a test: about 20 s per sky plus 7 s per grid atmosphere built on 2 cores.

    /usr/bin/python3 bench/table_family.py build/skyspec [--skies 6] [--seed 1] [--suns 30,5,0,-4]
        [--aerosol 5e-6,1.6e-4] [--alpha 0,2.5] [--ozone 200,450] [--out /tmp/skyspec-table-family]
"""
import argparse
import random
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from bench_stats import read_exr  # this folder's: the spectral channels S0.* of a skyspec EXR


def differences(img, ref):
    peak = ref.max(axis=-1)
    mask = peak > 1e-6 * peak.max()
    rel = (np.abs(img - ref) / np.maximum(np.abs(ref), 1e-30)).max(axis=-1)[mask]
    return np.median(rel), np.percentile(rel, 99), rel.max()


def render(skyspec, out, name, cache, sets, sun, size):
    env = {"SKYSPEC_CACHE_DIR": str(cache), "PATH": "/usr/bin:/bin"}
    cmd = [skyspec, "render", "-q", "--no-png", "--camera", "equirectangular", "--width", str(size[0]),
           "--height", str(size[1]), "--sun-elevation", str(sun), "--out", str(out), "--name", name]
    for s in sets:
        cmd += ["--set", s]
    t0 = time.monotonic()
    subprocess.run(cmd, check=True, env=env)
    return time.monotonic() - t0, out / f"{name}.exr"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("skyspec")
    ap.add_argument("--skies", type=int, default=6)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--suns", default="30,5,0,-4")
    ap.add_argument("--aerosol", default="5e-6,1.6e-4", help="range of atmosphere.mie.scattering_per_m (m^-1)")
    ap.add_argument("--alpha", default="0,2.5", help="range of atmosphere.mie.angstrom_exponent")
    ap.add_argument("--ozone", default="200,450", help="range of atmosphere.ozone.column_DU")
    ap.add_argument("--size", default="128x64")
    ap.add_argument("--out", default="/tmp/skyspec-table-family")
    a = ap.parse_args()
    skyspec = str(Path(a.skyspec).resolve())
    out = Path(a.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    grid_cache = out / "grid-cache"
    size = tuple(int(v) for v in a.size.split("x"))
    suns = [float(s) for s in a.suns.split(",")]
    rng = random.Random(a.seed)
    lo_b, hi_b = (float(v) for v in a.aerosol.split(","))
    lo_a, hi_a = (float(v) for v in a.alpha.split(","))
    lo_o, hi_o = (float(v) for v in a.ozone.split(","))
    print("| sky | aerosol (m^-1) | alpha | ozone (DU) | sun (deg) | median | p99 | largest | exact s | interpolated s |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    worst = 0.0
    for k in range(a.skies):
        beta, alpha, ozone = rng.uniform(lo_b, hi_b), rng.uniform(lo_a, hi_a), rng.uniform(lo_o, hi_o)
        sets = [f"atmosphere.mie.scattering_per_m={beta:.4g}", f"atmosphere.mie.angstrom_exponent={alpha:.3f}",
                f"atmosphere.ozone.column_DU={ozone:.1f}"]
        exact_cache = out / f"exact-cache-{k}"
        for sun in suns:
            name = f"sky{k}-sun{sun:g}"
            t_exact, exact = render(skyspec, out, name + "-exact", exact_cache, sets, sun, size)
            t_interp, interp = render(skyspec, out, name + "-interpolated", grid_cache,
                                      sets + ['render.ms_tables="interpolated"'], sun, size)
            med, p99, largest = differences(read_exr(interp)[0], read_exr(exact)[0])
            worst = max(worst, largest)
            print(f"| {k} | {beta:.3g} | {alpha:.2f} | {ozone:.0f} | {sun:g} | {100 * med:.4f} % | {100 * p99:.4f} % | "
                  f"{100 * largest:.4f} % | {t_exact:.1f} | {t_interp:.1f} |", flush=True)
        shutil.rmtree(exact_cache)
    grid = len(list(grid_cache.glob("orders-*.bin")))
    print(f"largest difference over every sky and sun: {100 * worst:.4f} %; grid atmospheres built: {grid}")


if __name__ == "__main__":
    sys.exit(main())
