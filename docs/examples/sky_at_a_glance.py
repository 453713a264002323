"""A first look at a skyspec sky from Python, in one script to copy and change.

Renders a panorama, reads the spectrum the sky sends from chosen directions, derives the Rayleigh
coefficients behind it from the refractive index of air and its number density, plots both, and
writes the EXR and PNG that `skyspec render` would write:

    python3 docs/examples/sky_at_a_glance.py --out sky-at-a-glance

Needs the skyspec module installed (`cmake --install build`, see docs/python.md), NumPy and
Matplotlib (Debian: python3-numpy, python3-matplotlib). The first run builds this atmosphere's
scattering tables (tens of seconds on 2 cores, with a progress bar on stderr); they are cached, and
later runs take a few seconds.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt
import numpy as np

import skyspec

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="sky-at-a-glance", help="output folder (created if missing)")
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)

# 1. A whole-sphere panorama in Blender's layout (north on +Y), the sun low in the south-west, every
#    5 nm. Any scene key of docs/scene-keys.md goes in `overrides`, flat or nested.
sky = skyspec.render(overrides={
    "camera": {"type": "equirectangular", "width": 256, "height": 128, "panorama_convention": "blender"},
    "sun": {"elevation_deg": 15, "azimuth_deg": 225},
    "spectrum": {"step_nm": 5},
}, progress=True)
print(sky)
print("exposure:", sky.exposure)
sky.write_exr(os.path.join(args.out, "sky.exr"))  # the spectral EXR, header and all
sky.write_png(os.path.join(args.out, "sky.png"))  # the sRGB preview at the recorded exposure

# 2. What the sky sends from a few directions (azimuth clockwise from north, elevation; degrees).
#    pixel() finds the pixel looking nearest; directions[row, column] is where it looks exactly.
looks = {
    "zenith": (0.0, 90.0),
    "90 deg round from the sun, 30 up": (sky.sun_azimuth_deg + 90.0, 30.0),
    "5 deg above the sun": (sky.sun_azimuth_deg, sky.sun_elevation_deg + 5.0),
    "the ground, 30 deg down": (sky.sun_azimuth_deg + 180.0, -30.0),
}
spectra = {}
for name, (azimuth, elevation) in looks.items():
    row, column = sky.pixel(azimuth, elevation)
    spectra[name] = sky.spectrum_at(azimuth, elevation)
    x, y, z = sky.directions[row, column]
    print(f"{name:34s} pixel ({row:3d}, {column:3d}) looks at azimuth "
          f"{np.degrees(np.arctan2(x, y)) % 360:6.1f}, elevation {np.degrees(np.arcsin(z)):5.1f}: "
          f"luminance {sky.xyz[row, column, 1]:8.1f} cd/m^2")

# 3. The coefficients behind it, for the same atmosphere: sigma(lambda) from n(lambda) and the King
#    factor, N from the U.S. Standard Atmosphere, beta = sigma N, and the vertical optical depth.
d = skyspec.derive(sky.wavelengths_nm, scene_toml=sky.scene_toml)
for nm in (450, 550, 650):
    i = int(np.argmin(np.abs(d["wavelength_nm"] - nm)))
    print(f"{nm} nm: n - 1 = {d['refractivity'][i]:.4e}, sigma = {d['cross_section_m2'][i]:.4e} m^2, "
          f"beta = {d['rayleigh_scattering_per_m'][0, i]:.4e} /m, tau = {d['rayleigh_optical_depth'][0, i]:.4f}")

# 4. One figure: the spectra, and the Rayleigh optical depth against lambda^-4.
figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
for name, spectrum in spectra.items():
    left.plot(sky.wavelengths_nm, spectrum, label=name)
left.set_yscale("log")
left.set(xlabel="wavelength (nm)", ylabel="spectral radiance (W m$^{-2}$ sr$^{-1}$ nm$^{-1}$)",
         title="What the sky sends")
left.legend(fontsize=8)
tau = d["rayleigh_optical_depth"][0]
right.plot(d["wavelength_nm"], tau, label="skyspec (derived)")
right.plot(d["wavelength_nm"], tau[np.argmin(np.abs(d["wavelength_nm"] - 550))] * (550 / d["wavelength_nm"]) ** 4, "--",
           label=r"$\lambda^{-4}$ through 550 nm")
right.set(xlabel="wavelength (nm)", ylabel="vertical optical depth", title="Rayleigh optical depth at sea level")
right.legend(fontsize=8)
figure.tight_layout()
figure.savefig(os.path.join(args.out, "spectra.png"), dpi=100)
print("wrote", ", ".join(os.path.join(args.out, f) for f in ("sky.exr", "sky.png", "spectra.png")))

# Checks, so that a broken install or a wrong physics change does not pass quietly: everything is
# finite, the zenith is blue (more radiance at 450 than at 650 nm), the ground below the horizon
# is lit (a panorama gets a 0.25 albedo), and Bodhaine et al. (1999) give 0.0973 at 550 nm for
# 1013.25 hPa (within 1 %).
zenith = spectra["zenith"]
at = lambda nm: int(np.argmin(np.abs(sky.wavelengths_nm - nm)))  # noqa: E731
assert np.isfinite(sky.spectral).all() and np.isfinite(tau).all()
assert zenith[at(450)] > zenith[at(650)], "the zenith is not blue"
assert spectra["the ground, 30 deg down"].max() > 0, "the ground is black"
assert abs(tau[np.argmin(np.abs(d["wavelength_nm"] - 550))] / 0.0973 - 1) < 0.01
