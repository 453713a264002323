#!/usr/bin/env python3
"""Fits the exponential sums of data/gases/exponential_sums.csv (README.md in data/).

Bird & Riordan's (1986) band transmittance of a gas along a path with absorber amount u (water
vapour: precipitable centimetres; the uniformly mixed gases: air masses) at a wavelength with
band coefficient a is

    T(x) = exp(-c1 x / (1 + c2 x)^0.45),  x = a u,
    water vapour c1 = 0.2385, c2 = 20.07; mixed gases c1 = 1.41, c2 = 118.93.

Light transport needs Beer-Lambert's law, so T is written as a sum of exponentials,
T(x) ~ sum_i w_i exp(-k_i x) with w_i > 0, sum w_i = 1 (T is completely monotone in x: its
exponent is a Bernstein function, so such a sum exists). k_i and w_i are fitted by least squares
on 0 and 1200 logarithmically spaced x from 1e-6 to 1e7. Run with Debian's python3 (numpy, scipy):

    /usr/bin/python3 data/gases/make_exponential_sums.py > data/gases/exponential_sums.csv
"""
import numpy as np
from scipy.optimize import least_squares

TERMS = 5
GASES = [("water_vapour", 0.2385, 20.07), ("mixed_gases", 1.41, 118.93)]


def band_transmittance(x, c1, c2):
    return np.exp(-c1 * x / (1.0 + c2 * x) ** 0.45)


def fit(c1, c2):
    x = np.concatenate([[0.0], np.logspace(-6, 7, 1200)])
    t = band_transmittance(x, c1, c2)
    # Start from rates spread over the decades where T falls from 1 to 0, equal weights.
    start = np.concatenate([np.log(np.logspace(-3, 1, TERMS) * c1 / 0.2385 * 20.07 / c2), np.zeros(TERMS)])

    def unpack(p):
        k = np.exp(p[:TERMS])
        w = np.exp(p[TERMS:])
        return k, w / w.sum()

    def residual(p):
        k, w = unpack(p)
        return np.exp(-np.outer(x, k)) @ w - t

    with np.errstate(over="ignore", invalid="ignore"):
        result = least_squares(residual, start, method="lm", max_nfev=200000, xtol=1e-14, ftol=1e-14)
    k, w = unpack(result.x)
    order = np.argsort(k)
    return k[order], w[order], np.abs(residual(result.x)).max()


print("# Exponential sums of Bird & Riordan's (1986) band transmittances: T(x) = sum w exp(-k x),")
print("# x = band coefficient times absorber amount. Written by data/gases/make_exponential_sums.py.")
print("gas,term,k,weight")
for name, c1, c2 in GASES:
    k, w, err = fit(c1, c2)
    print(f"# {name}: largest |sum - T| {err:.2e}")
    for i in range(TERMS):
        print(f"{name},{i},{k[i]:.10e},{w[i]:.10e}")
