#!/usr/bin/python3
"""Prints the multiple-scattering budget from the renders of bench/ms_budget.sh (its folder)."""
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def read(path):
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise SystemExit(f"ms_budget.py: cannot read {path}: {oiio.geterror()}")
    spec = inp.spec()
    px = np.asarray(inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT))
    inp.close()
    idx = [k for k, n in enumerate(spec.channelnames) if n.startswith("S0.")]
    wl = [float(spec.channelnames[k][3:-2].replace(",", ".")) for k in idx]
    return px[:, :, idx].astype(np.float64), wl


def main():
    out = Path(sys.argv[1])
    base, wl = read(out / "orders6.exr")
    for name, what in (("orders12", "6 orders instead of 12"), ("tables32x144", "16 x 72 tables instead of 32 x 144")):
        other, _ = read(out / f"{name}.exr")
        lit = other.max(axis=-1) > 1e-6 * other.max()  # the fisheye's corners are black
        cells = []
        for nm in (380, 400, 450, 550, 650):
            i = wl.index(nm)
            rel = np.abs(base[..., i] - other[..., i])[lit] / other[..., i][lit]
            cells.append(f"{nm} nm p50 {np.percentile(rel, 50):.1e} p99 {np.percentile(rel, 99):.1e}")
        print(f"{what}: " + "; ".join(cells))
    six, _ = read(out / "zenith6.exr")
    one, _ = read(out / "zenith1.exr")
    c = six.shape[0] // 2
    print("higher orders at the zenith (sun 30 degrees): "
          + ", ".join(f"{nm} nm +{100 * (six[c, c, wl.index(nm)] / one[c, c, wl.index(nm)] - 1):.1f} %" for nm in (450, 550, 650)))


if __name__ == "__main__":
    main()
