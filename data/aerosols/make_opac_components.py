#!/usr/bin/python3
"""Compile data/aerosols/opac_components.csv from OPAC 3.1's component files.

Usage: make_opac_components.py OPAC_DATA_DIR > opac_components.csv

OPAC_DATA_DIR holds OPAC's output files per component and relative humidity (inso00, waso00 ..
waso99, ...), as distributed in github.com/aubema/illumina, Aerosol_optics/OPAC_data/. Each file
gives the component's lognormal size distribution and, per wavelength, its refractive index and
the optical properties OPAC computed from them (per particle per cm^3). This keeps the header's
distribution, and the rows from 0.25 to 2.5 um: the refractive index that skyspec integrates and
OPAC's single-scattering albedo, asymmetry parameter and extinction, which tests compare with.
The imaginary index is written as its magnitude (OPAC writes it negative).
"""
import os
import re
import sys

COMPONENTS = ["inso", "waso", "soot", "ssam", "sscm", "minm", "miam", "micm", "mitr", "suso"]
HUMIDITIES = ["00", "50", "70", "80", "90", "95", "98", "99"]
MAX_WAVELENGTH_UM = 2.5


def header_value(lines, label):
    for line in lines:
        if label in line:
            return float(line.split(":")[1])
    raise SystemExit(f"no '{label}' in the file")


def main():
    folder = sys.argv[1]
    out = sys.stdout
    out.write("# OPAC 3.1 aerosol components (Hess, Koepke & Schult 1998, BAMS 79, 831): lognormal size\n")
    out.write("# distribution (number), refractive index and OPAC's optical properties per wavelength.\n")
    out.write("# Compiled by data/aerosols/make_opac_components.py; data/README.md has the source.\n")
    out.write("# radii in um; ext_per_km: extinction coefficient for 1 particle per cm^3; m_im >= 0.\n")
    out.write("component,rh_percent,r_min_um,r_max_um,sigma,r_mod_wet_um,r_mod_dry_um,"
              "wavelength_um,m_re,m_im,ext_per_km,single_scattering_albedo,asymmetry\n")
    for comp in COMPONENTS:
        for rh in HUMIDITIES:
            path = os.path.join(folder, comp + rh)
            if not os.path.exists(path):
                continue
            lines = open(path).read().splitlines()
            dist = [header_value(lines, k) for k in
                    ("minimum radius", "maximum radius", "sigma", "Rmod (wet)", "Rmod (dry)")]
            start = next(i for i, l in enumerate(lines) if l.startswith("# wavelength")) + 3
            for line in lines[start:]:
                # Fixed-width fields may touch ("1.213E-03-1.446E-10"): read numbers, not words.
                f = re.findall(r"[-+]?\d+\.\d+E[-+]\d+", line)
                if len(f) != 9:
                    break
                wl, ext, sca, ab, ssa, g, extnor, mre, mim = (float(x) for x in f)
                if wl > MAX_WAVELENGTH_UM + 1e-9:
                    break
                out.write(f"{comp},{int(rh)},{dist[0]:.4g},{dist[1]:.4g},{dist[2]:.4g},{dist[3]:.4g},"
                          f"{dist[4]:.4g},{wl:.4g},{mre:.4g},{abs(mim):.4g},{ext:.4g},{ssa:.4g},{g:.4g}\n")


main()
