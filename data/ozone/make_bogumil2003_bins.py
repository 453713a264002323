#!/usr/bin/env python3
"""Writes data/ozone/bogumil2003_233K.csv from the SCIAMACHY ozone cross-sections.

Input: the two published data files of Bogumil, Orphal & Burrows (version 3.0, December 2004),
223 K and 243 K, two columns each: vacuum wavelength in nm, cross-section in cm^2 per molecule
(lines of the form "229.9956  4.61999E-18" or "{229.9956,  4.61999E-18},"; comments are skipped).
Where they were obtained and how they were checked: data/README.md.

Output: bin means at 233 K (the mean of the two temperatures, i.e. linear interpolation in
temperature to 233 K, the temperature of the Serdyuchenko table used between 360 and 840 nm),
in m^2 per molecule, over 1 nm bins from 230 to 360 nm (the Hartley and Huggins bands change by
a factor of e within a few nm) and 10 nm bins from 840 to 1060 nm (the last full bin both files
cover). The mean over [lo, hi] is the integral of the data's linear interpolant divided by hi - lo.

Usage: make_bogumil2003_bins.py BOGUMIL_223K BOGUMIL_243K > data/ozone/bogumil2003_233K.csv
"""
import re
import sys

import numpy as np

NUMBER_PAIR = re.compile(r"^\s*\{?\s*([0-9]+\.[0-9]*)\s*,?\s+([-+0-9.Ee]+)\s*\}?,?\s*$")


def read_points(path):
    points = [tuple(map(float, m.groups())) for line in open(path) if (m := NUMBER_PAIR.match(line))]
    data = np.array(points)
    if len(data) < 1000 or np.any(np.diff(data[:, 0]) <= 0):
        sys.exit(f"{path}: expected over 1000 rows with increasing wavelengths")
    return data


def bin_mean(data, lo, hi):
    w, s = data[:, 0], data[:, 1]
    if lo < w[0] or hi > w[-1]:
        sys.exit(f"bin {lo}-{hi} nm lies outside the data ({w[0]}-{w[-1]} nm)")
    x = np.concatenate([[lo], w[(w > lo) & (w < hi)], [hi]])
    y = np.interp(x, w, s)
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)) / (hi - lo))


def main():
    cold, warm = read_points(sys.argv[1]), read_points(sys.argv[2])
    bins = [(lo, lo + 1) for lo in range(230, 360)] + [(lo, lo + 10) for lo in range(840, 1060, 10)]
    print("# Ozone (O3) absorption cross-section at 233 K, bin means, 230-360 nm (1 nm bins) and 840-1060 nm")
    print("# (10 nm bins): the ultraviolet and near-infrared ends of the built-in table; 360-840 nm is")
    print("# serdyuchenko2014_233K_10nm.csv. Columns: bin edges in nm (vacuum wavelengths); mean cross-section")
    print("# over [lower_nm, upper_nm) in m^2 per molecule (1 m^2 = 1e4 cm^2).")
    print("# Laboratory data: Bogumil, Orphal & Burrows 2003 (SCIAMACHY flight model, version 3.0), the mean of")
    print("# the 223 K and 243 K spectra. Written by data/ozone/make_bogumil2003_bins.py; source and checks:")
    print("# data/README.md, section ozone/bogumil2003_233K.csv.")
    print("lower_nm,upper_nm,cross_section_m2")
    for lo, hi in bins:
        mean_cm2 = 0.5 * (bin_mean(cold, lo, hi) + bin_mean(warm, lo, hi))
        if mean_cm2 <= 0:
            sys.exit(f"bin {lo}-{hi} nm: mean {mean_cm2} <= 0")
        print(f"{lo},{hi},{mean_cm2 * 1e-4:.4g}")


if __name__ == "__main__":
    main()
