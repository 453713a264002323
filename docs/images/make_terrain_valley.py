#!/usr/bin/python3
"""Writes terrain-valley.png, the height map of docs/images/terrain-valley.toml: a valley running
north-south between two ranges, as a 16-bit PNG (codes 0-65535 over 0-3000 m: the scene's
terrain.heightmap.height_scale_m = 3000), 91 x 201 pixels 200 m apart (18 x 40 km), its top row north.

    h(x, y) = floor(y) + sum over the ranges of H_k (1 + 0.15 sin(2 pi y / L_k + phi_k)) exp(-((x - x_k) / w_k)^2)

x east and y north of the map's centre (metres); the valley floor rises from 300 m in the south to
500 m in the north; the western range (H = 1900 m at x = -5 km) is higher than the eastern one
(H = 1500 m at x = +5.5 km); everything falls to 0 over the map's outer 3 km (cos^2), so the map
meets the sphere around it without a cliff. Run with Debian's python3 (numpy) and oiiotool.
"""
import os
import subprocess

import numpy as np

WIDTH, HEIGHT, PIXEL_M, SCALE_M = 91, 201, 200.0, 3000.0


def heights():
    x = (np.arange(WIDTH) - (WIDTH - 1) / 2) * PIXEL_M
    y = ((HEIGHT - 1) / 2 - np.arange(HEIGHT)) * PIXEL_M  # row 0 is north
    X, Y = np.meshgrid(x, y)
    h = 400.0 + 100.0 * Y / Y.max()
    for x_k, h_k, w_k, l_k, phi_k in ((-5000.0, 1900.0, 2500.0, 7000.0, 0.3), (5500.0, 1500.0, 2200.0, 5500.0, 1.9)):
        h += h_k * (1.0 + 0.15 * np.sin(2.0 * np.pi * Y / l_k + phi_k)) * np.exp(-(((X - x_k) / w_k) ** 2))
    # The outer 3 km fall to 0.
    def taper(d):
        return np.where(d < 3000.0, np.sin(0.5 * np.pi * np.clip(d, 0.0, 3000.0) / 3000.0) ** 2, 1.0)
    h *= taper(x.max() - np.abs(X)) * taper(y.max() - np.abs(Y))
    return h


def main():
    codes = np.round(np.clip(heights() / SCALE_M, 0.0, 1.0) * 65535.0).astype(">u2")  # big-endian, as PGM has it
    here = os.path.dirname(os.path.abspath(__file__))
    pgm, png = os.path.join(here, "terrain-valley.pgm"), os.path.join(here, "terrain-valley.png")
    with open(pgm, "wb") as f:  # binary PGM, 16 bits
        f.write(b"P5\n%d %d\n65535\n" % (WIDTH, HEIGHT))
        f.write(codes.tobytes())
    subprocess.run(["oiiotool", pgm, "-d", "uint16", "-o", png], check=True)
    os.remove(pgm)
    print(png, codes.max() / 65535.0 * SCALE_M, "m at the highest")


if __name__ == "__main__":
    main()
