#!/usr/bin/python3
"""Draws the contrast of an image's stripes: each pixel's green (linear Rec.709, from the spectral
EXR skyspec wrote) over the mean of the 61 pixels around it in its row, as grey from 0.96 (black) to
1.04 (white). Faint stripes across a smooth sky (anticrepuscular rays: a few per cent) show up; the
sky's own gradients, smooth over 61 pixels, do not. Prints the largest departure from 1 above the
horizon row given.

    make_ray_contrast.py RENDER.exr OUT.png HORIZON_ROW

Debian's python3 (numpy, OpenImageIO) and oiiotool.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio
from numpy.lib.stride_tricks import sliding_window_view

WINDOW, LOW, HIGH = 61, 0.96, 1.04


def main():
    exr, png, horizon = sys.argv[1], sys.argv[2], int(sys.argv[3])
    image = oiio.ImageBuf(exr)
    green = image.get_pixels(oiio.FLOAT)[:, :, image.spec().channelnames.index("G")]
    padded = np.pad(green, ((0, 0), (WINDOW // 2, WINDOW // 2)), mode="edge")
    ratio = green / sliding_window_view(padded, WINDOW, axis=1).mean(axis=2)
    sky = ratio[:horizon, WINDOW // 2 : -(WINDOW // 2)]
    print("largest departure above the horizon: %.1f %%" % (100.0 * np.abs(sky - 1.0).max()))
    grey = (np.clip((ratio - LOW) / (HIGH - LOW), 0.0, 1.0) * 255.0).round().astype(np.uint8)
    with tempfile.TemporaryDirectory() as tmp:
        pgm = os.path.join(tmp, "contrast.pgm")
        with open(pgm, "wb") as f:
            f.write(b"P5\n%d %d\n255\n" % (grey.shape[1], grey.shape[0]))
            f.write(grey.tobytes())
        subprocess.run(["oiiotool", pgm, "-o", png], check=True)


if __name__ == "__main__":
    main()
