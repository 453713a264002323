"""The `skyspec` Python module against the command-line program it shares its library with.

Run by CTest with PYTHONPATH pointing at the built module and SKYSPEC_CLI at the program:
    PYTHONPATH=build/python SKYSPEC_CLI=build/skyspec /usr/bin/python3 -m unittest tests/python/test_module.py
The derivation must equal the CLI's JSON report number for number, a render must equal the CLI's
spectral EXR (read with OpenImageIO) pixel for pixel, and published values must come out right.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import skyspec

CLI = os.environ.get("SKYSPEC_CLI", "skyspec")


def cli(*args):
    done = subprocess.run([CLI, *args], capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError(f"skyspec {' '.join(args)} failed: {done.stderr}")
    return done.stdout


# Small scattering-order tables (one table order, harmonics to degree 4) and every pixel marched, for the tests
# that compare the module with the program on the same scene (not the physics: test_multiple_
# scattering and docs/validation.md check that): both sides read the same tables.
SMALL_TABLES = {"render.ms_altitude_samples": 8, "render.ms_sun_samples": 24, "render.scattering_orders": 2,
                "render.ms_angular_degree": 4, "render.sky_view_table": False}


def set_args(overrides):
    """--set KEY=VALUE arguments of the program for a flat dict of scene keys."""
    args = []
    for key, value in overrides.items():
        args += ["--set", f"{key}={str(value).lower() if isinstance(value, bool) else value}"]
    return args


def cli_json(*args):
    return json.loads(cli("coefficients", "--format", "json", *args))


class DeriveAgainstCli(unittest.TestCase):
    def assert_same(self, a, b, what):
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        self.assertEqual(a.shape, b.shape, what)
        np.testing.assert_allclose(a, b, rtol=1e-15, atol=0, err_msg=what)

    def test_cold_thin_air_and_two_altitudes(self):
        j = cli_json("--pressure", "250hPa", "--temperature", "220K", "--altitudes", "0,5000")
        d = skyspec.derive(pressure_Pa=25000, temperature_K=220, altitudes_m=[0, 5000])
        self.assert_same(d["wavelength_nm"], j["wavelength_nm"], "wavelengths")
        for key, jkey in [("refractivity", "refractivity"), ("refractivity_formula_co2", "refractivity_formula_co2"),
                          ("king_factor_air", "king_factor_air"), ("king_factor_n2", "king_factor_n2"),
                          ("king_factor_o2", "king_factor_o2"), ("cross_section_m2", "cross_section_m2")]:
            self.assert_same(d[key], j["rayleigh"][jkey], key)
        self.assert_same(d["altitude_m"], [lv["altitude_m"] for lv in j["levels"]], "altitudes")
        self.assert_same(d["number_density_per_m3"], [lv["number_density_per_m3"] for lv in j["levels"]], "N")
        for key in ["rayleigh_scattering_per_m", "rayleigh_optical_depth", "mie_scattering_per_m",
                    "mie_extinction_per_m", "mie_optical_depth", "ozone_optical_depth", "total_optical_depth"]:
            self.assert_same(d[key], [lv[key] for lv in j["levels"]], key)
        c = j["conditions"]
        self.assertEqual(d["conditions_number_density_per_m3"], c["number_density_per_m3"])
        self.assert_same(d["conditions_rayleigh_scattering_per_m"], c["rayleigh_scattering_per_m"], "beta(P, T)")
        self.assert_same(d["conditions_rayleigh_optical_depth_above"], c["rayleigh_optical_depth_above"], "tau above")
        self.assert_same(d["conditions_refractivity"], c["refractivity"], "n - 1 at (P, T)")
        # N = P / (k T) for 250 hPa and 220 K, and beta = sigma N.
        n = 25000 / (1.380649e-23 * 220)
        self.assertAlmostEqual(d["conditions_number_density_per_m3"] / n, 1.0, places=14)
        np.testing.assert_allclose(d["conditions_rayleigh_scattering_per_m"], d["cross_section_m2"] * n, rtol=1e-14)

    def test_seed_preset_and_options(self):
        j = cli_json("--preset", "seed", "--refractive-index", "ciddor", "--co2-ppm", "360")
        d = skyspec.derive(preset="seed", refractive_index="ciddor", co2_ppm=360)
        self.assertEqual(d["rayleigh_source"], "fixed")
        self.assertEqual(j["rayleigh"]["source"], "fixed")
        self.assert_same(d["wavelength_nm"], [440, 550, 680], "seed grid")
        self.assert_same(d["cross_section_m2"], j["rayleigh"]["cross_section_m2"], "sigma")
        self.assert_same(d["rayleigh_scattering_per_m"][0], [33.1e-6, 13.5e-6, 5.8e-6], "typed-in beta")

    def test_report_text_is_the_cli_report(self):
        args = ["--wavelengths", "400,500,600", "--altitudes", "0,1000"]
        from_cli = json.loads(cli("coefficients", "--format", "json", *args))
        from_module = json.loads(skyspec.coefficient_report("json", wavelengths_nm=[400, 500, 600], altitudes_m=[0, 1000]))
        from_cli.pop("origin")
        from_module.pop("origin")
        self.assertEqual(from_cli, from_module)
        self.assertIn("<svg", skyspec.coefficient_report("html", wavelengths_nm=[400, 500, 600]))


class RenderAgainstCli(unittest.TestCase):
    def test_spectral_image_equals_the_exr(self):
        import OpenImageIO as oiio
        overrides = {"camera.width": 12, "camera.height": 8, "camera.type": "equirectangular",
                     "sun.elevation_deg": 10, "render.table_altitude_samples": 32, "render.table_zenith_samples": 64,
                     **SMALL_TABLES}
        img = skyspec.render(overrides=overrides)
        self.assertEqual(img.spectral.shape, (8, 12, 41))
        self.assertEqual(img.spectral.dtype, np.float32)
        np.testing.assert_array_equal(img.wavelengths_nm, np.arange(380, 781, 10))
        self.assertTrue(np.isfinite(img.spectral).all())
        with tempfile.TemporaryDirectory() as tmp:
            cli("render", "-q", "--out", tmp, "--no-png", "--width", "12", "--height", "8", "--camera", "equirectangular",
                "--sun-elevation", "10", "--set", "render.table_altitude_samples=32",
                "--set", "render.table_zenith_samples=64", *set_args(SMALL_TABLES))
            exr = oiio.ImageBuf(os.path.join(tmp, "sky.exr"))
            names = list(exr.spec().channelnames)
            pixels = exr.get_pixels(oiio.FLOAT)
        for i, nm in enumerate(img.wavelengths_nm):
            channel = names.index(f"S0.{int(nm)},000000nm")
            np.testing.assert_array_equal(pixels[:, :, channel], img.spectral[:, :, i], err_msg=f"{nm} nm")
        for c, name in enumerate("RGB"):
            np.testing.assert_array_equal(pixels[:, :, names.index(name)], img.rgb[:, :, c], err_msg=name)
        # XYZ -> linear Rec.709 (IEC 61966-2-1) gives back the RGB.
        m = np.array([[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560],
                      [0.0556434, -0.2040259, 1.0572252]])
        rgb = img.xyz.astype(np.float64) @ m.T
        np.testing.assert_allclose(rgb, img.rgb, rtol=2e-3, atol=1e-3 * float(np.abs(img.rgb).max()))

    def test_polarised_image_equals_the_exr(self):
        # stokes (h, w, n, 4) holds the EXR's S0-S3; e1 is perpendicular to each pixel's direction.
        import OpenImageIO as oiio
        overrides = {"camera.width": 8, "camera.height": 4, "camera.type": "equirectangular",
                     "spectrum.wavelengths_nm": [450, 650], "output.polarisation": True, **SMALL_TABLES}
        img = skyspec.render(overrides=overrides)
        self.assertEqual(img.stokes.shape, (4, 8, 2, 4))
        np.testing.assert_array_equal(img.stokes[..., 0], img.spectral)
        self.assertTrue((img.stokes[..., 3] == 0).all())
        self.assertTrue((np.hypot(img.stokes[..., 1], img.stokes[..., 2]) <= img.stokes[..., 0]).all())
        np.testing.assert_allclose(np.einsum("hwc,hwc->hw", img.stokes_e1, img.directions), 0.0, atol=1e-12)
        with tempfile.TemporaryDirectory() as tmp:
            cli("render", "-q", "--out", tmp, "--no-png", "--width", "8", "--height", "4", "--camera", "equirectangular",
                "--set", "spectrum.wavelengths_nm=[450, 650]", "--set", "output.polarisation=true",
                *set_args(SMALL_TABLES))
            exr = oiio.ImageBuf(os.path.join(tmp, "sky.exr"))
            names = list(exr.spec().channelnames)
            pixels = exr.get_pixels(oiio.FLOAT)
        for i, nm in enumerate(img.wavelengths_nm):
            for c in range(4):
                np.testing.assert_array_equal(pixels[:, :, names.index(f"S{c}.{int(nm)},000000nm")], img.stokes[:, :, i, c])
        self.assertIsNone(skyspec.render(overrides={"camera.width": 2, "camera.height": 2}).stokes)

    def test_result_writes_the_files_the_cli_writes(self):
        # write_exr / write_png of a render in memory are the CLI's files for the same scene: the same
        # pixels, PNG code values and header (scene, exposure as a double, units, envmap).
        import OpenImageIO as oiio
        overrides = {"camera.width": 16, "camera.height": 8, "camera.type": "equirectangular",
                     "camera.panorama_convention": "blender", "sun.elevation_deg": 12, "sun.azimuth_deg": 200,
                     "render.scattering_orders": 1, "spectrum.count": 6}
        with tempfile.TemporaryDirectory() as tmp:
            img = skyspec.render(overrides=dict(overrides, **{"output.directory": tmp}))
            cli("render", "-q", "--scene", self.write_scene(tmp, img.scene_toml))
            img.write_exr(os.path.join(tmp, "py.exr"))
            scale = img.write_png(os.path.join(tmp, "py.png"))
            self.assertEqual(scale, img.exposure_scale)
            a, b = oiio.ImageBuf(os.path.join(tmp, "sky.exr")), oiio.ImageBuf(os.path.join(tmp, "py.exr"))
            np.testing.assert_array_equal(a.get_pixels(oiio.FLOAT), b.get_pixels(oiio.FLOAT))
            self.assertEqual(list(a.spec().channelnames), list(b.spec().channelnames))
            for key in ["skyspec:scene", "skyspec:units", "skyspec:exposure", "skyspec:exposureScale",
                        "skyspec:wavelengths", "skyspec:sunRGB", "textureformat", "chromaticities"]:
                self.assertEqual(a.spec().getattribute(key), b.spec().getattribute(key), key)
            self.assertEqual(b.spec().getattribute("skyspec:exposureScale"), img.exposure_scale)
            pa = oiio.ImageBuf(os.path.join(tmp, "sky.png")).get_pixels(oiio.UINT8)
            pb = oiio.ImageBuf(os.path.join(tmp, "py.png")).get_pixels(oiio.UINT8)
            np.testing.assert_array_equal(pa, pb)
            # Another display through the same call; a bad name is a ValueError naming it.
            img.write_png(os.path.join(tmp, "p3.png"), display="Display P3", bits=16)
            self.assertEqual(oiio.ImageBuf(os.path.join(tmp, "p3.png")).spec().format, oiio.UINT16)
            with self.assertRaises(ValueError) as e:
                img.write_png(os.path.join(tmp, "x.png"), view="Filmic")
            self.assertIn("Un-tone-mapped", str(e.exception))
            self.assertTrue(str(e.exception).startswith('view = "Filmic"'), str(e.exception))  # the keyword, not --view
            self.assertFalse(os.path.exists(os.path.join(tmp, "x.png")))
            # A NaN put into the arrays is refused, and nothing is written.
            img.rgb[0, 0, 0] = np.nan
            with self.assertRaises(Exception):
                img.write_png(os.path.join(tmp, "nan.png"))
            self.assertFalse(os.path.exists(os.path.join(tmp, "nan.png")))

    @staticmethod
    def write_scene(folder, text):
        path = os.path.join(folder, "scene.toml")
        with open(path, "w") as f:
            f.write(text)
        return path

    def test_aerial_perspective_equals_the_cli(self):
        """skyspec.aerial_perspective is `skyspec aerial` without files: the same transmittance and inscatter."""
        import OpenImageIO as oiio
        depth = np.full((6, 10), 5000.0, dtype=np.float32)
        depth[0, :] = np.inf  # sky
        overrides = {"camera.type": "perspective", "sun.elevation_deg": 20,
                     "render.table_altitude_samples": 32, "render.table_zenith_samples": 64, **SMALL_TABLES}
        ap = skyspec.aerial_perspective(depth, overrides=overrides)
        self.assertEqual(ap["transmittance"].shape, (6, 10, 41))
        self.assertEqual(ap["inscatter_rgb"].shape, (6, 10, 3))
        with tempfile.TemporaryDirectory() as tmp:
            buf = oiio.ImageBuf(oiio.ImageSpec(10, 6, 1, oiio.FLOAT))
            spec = buf.spec()
            spec.channelnames = ("Z",)
            buf = oiio.ImageBuf(spec)
            buf.set_pixels(oiio.ROI(0, 10, 0, 6, 0, 1, 0, 1), depth.reshape(6, 10, 1))
            buf.write(os.path.join(tmp, "depth.exr"))
            args = ["aerial", "-q", "--depth", os.path.join(tmp, "depth.exr"), "--camera", "perspective",
                    "--sun-elevation", "20", "--out", tmp, "--name", "ap",
                    *set_args({k: v for k, v in overrides.items() if k.startswith("render.")})]
            cli(*args)
            for name, key in (("ap_transmittance.exr", "transmittance"), ("ap_inscatter.exr", "inscatter")):
                exr = oiio.ImageBuf(os.path.join(tmp, name))
                names = list(exr.spec().channelnames)
                pixels = exr.get_pixels(oiio.FLOAT)
                for i, nm in enumerate(ap["wavelengths_nm"]):
                    channel = names.index(f"S0.{int(nm)},000000nm")
                    np.testing.assert_array_equal(pixels[:, :, channel], ap[key][:, :, i], err_msg=f"{name} {nm} nm")
        # Along the same rays, the whole way to space (or to the ground, for the rays below the horizon:
        # rows 3-5) scatters more light in and lets less through than 5 km of it.
        sky = skyspec.aerial_perspective(np.full((6, 10), np.inf), overrides=overrides)
        self.assertTrue((sky["inscatter"] >= ap["inscatter"]).all())
        self.assertTrue((sky["inscatter"][1:3] > ap["inscatter"][1:3]).all())
        self.assertTrue((sky["transmittance"][1:3] < ap["transmittance"][1:3]).all())
        np.testing.assert_array_equal(sky["inscatter"][0], ap["inscatter"][0])
        with self.assertRaises(ValueError) as e:
            skyspec.aerial_perspective(np.full((2, 2), -1.0), overrides=overrides)
        self.assertIn("depth = pixel (0, 0)", str(e.exception))

    def test_result_says_where_each_pixel_looks(self):
        # Directions: unit vectors; for a Blender-layout panorama the column of azimuth A is
        # (A / 360 + 1/4) of the width (Cycles' mapping with north on +Y). The sun's vector is its
        # azimuth and elevation; the scene comes back as TOML and as a dict.
        img = skyspec.render(overrides={"camera.width": 72, "camera.height": 36, "camera.type": "equirectangular",
                                        "camera.panorama_convention": "blender", "sun.elevation_deg": 25,
                                        "sun.azimuth_deg": 150, "render.scattering_orders": 1, "spectrum.count": 4})
        d = img.directions
        self.assertEqual(d.shape, (36, 72, 3))
        with self.assertRaises(ValueError):  # where the render looks is not for editing
            d[0, 0, 0] = 1.0
        np.testing.assert_allclose(np.linalg.norm(d, axis=2), 1.0, rtol=1e-12)
        self.assertTrue(img.valid.all())
        row, column = img.pixel(azimuth_deg=92, elevation_deg=1)  # east: the centre, just above the horizon
        self.assertEqual((row, column), (17, 36))
        az, el = np.radians(150), np.radians(25)
        np.testing.assert_allclose(img.sun_direction, [np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)],
                                   atol=1e-12)
        self.assertEqual((img.sun_azimuth_deg, img.sun_elevation_deg), (150, 25))
        row, column = img.pixel(150, 25)
        np.testing.assert_array_equal(img.spectrum_at(150, 25), img.spectral[row, column])
        self.assertEqual(column, int((150 / 360 + 0.25) * 72))
        self.assertEqual(img.scene["camera"]["panorama_convention"], "blender")
        self.assertEqual(img.scene["ground"]["albedo"], 0.25)  # a panorama's ground
        self.assertIn('panorama_convention = "blender"', img.scene_toml)
        self.assertGreater(img.exposure_scale, 0)
        self.assertAlmostEqual(img.exposure_ev, np.log2(img.exposure_scale))
        self.assertIn("automatic", img.exposure)
        again = skyspec.render(scene_toml=img.scene_toml)  # the recorded scene renders the same pixels
        np.testing.assert_array_equal(again.spectral, img.spectral)
        # A fisheye's corners look nowhere.
        fish = skyspec.render(overrides={"camera.width": 8, "camera.height": 8, "render.scattering_orders": 1,
                                         "spectrum.count": 4})
        self.assertFalse(fish.valid[0, 0])
        np.testing.assert_array_equal(fish.directions[0, 0], [0, 0, 0])
        with self.assertRaises(ValueError):
            fish.pixel(0, 95)

    def test_bad_override_names_the_key(self):
        with self.assertRaises(ValueError) as e:
            skyspec.render(overrides={"camera": {"width": -5}})
        self.assertIn("camera.width", str(e.exception))
        with self.assertRaises(ValueError) as e:
            skyspec.derive(overrides={"atmosphere.rayleigh.co2": 400})
        self.assertIn("unknown key", str(e.exception))


class TimelapseAgainstCli(unittest.TestCase):
    """skyspec.timelapse is `skyspec timelapse`: the same frames, byte for byte, and the same resume."""

    def test_timelapse_equals_the_cli(self):
        overrides = {"camera.width": 12, "camera.height": 12, "render.scattering_orders": 1,
                     "location.latitude_deg": 48.14, "location.longitude_deg": 11.58}
        times = ("2026-06-21T20:00:00+02:00", "2026-06-21T20:30:00+02:00")
        with tempfile.TemporaryDirectory() as tmp:
            got = skyspec.timelapse(*times, 15, overrides=overrides, out=os.path.join(tmp, "py"), name="dusk")
            self.assertEqual((got["frames"], got["written"], got["kept"], got["failed"]), (3, 3, 0, 0))
            self.assertTrue(got["exposure"].startswith("metered on frame 0"), got["exposure"])
            self.assertEqual([os.path.basename(f) for f in got["files"]],
                             [f"dusk_{k:04d}.{e}" for k in range(3) for e in ("exr", "png")])
            cli("timelapse", "-q", "--start", times[0], "--end", times[1], "--step-minutes", "15",
                "--out", os.path.join(tmp, "cli"), "--name", "dusk", *set_args(overrides))
            for f in got["files"]:
                with open(f, "rb") as a, open(os.path.join(tmp, "cli", os.path.basename(f)), "rb") as b:
                    self.assertEqual(a.read(), b.read(), os.path.basename(f))
            with open(got["manifest"]) as m:
                self.assertEqual(len(m.read().splitlines()), 3)
            again = skyspec.timelapse(*times, 15, overrides=overrides, out=os.path.join(tmp, "py"), name="dusk",
                                      resume=True, frames="1-2")
            self.assertEqual((again["first"], again["last"], again["written"], again["kept"]), (1, 3, 0, 2))
            with self.assertRaises(ValueError) as e:
                skyspec.timelapse(times[1], times[0], 15, overrides=overrides, out=tmp)
            self.assertIn("end", str(e.exception))
            self.assertNotIn("--end", str(e.exception))
            with self.assertRaises(ValueError) as e:
                skyspec.timelapse(*times, 15, overrides=overrides, out=tmp, frames="5-6")
            self.assertIn("frames", str(e.exception))


class MonteCarloAgainstCli(unittest.TestCase):
    def test_reference_equals_the_cli_json(self):
        overrides = {"spectrum.wavelengths_nm": [450, 650], "sun.elevation_deg": 15}
        r = skyspec.monte_carlo(overrides=overrides, probes=[(0, 90), (90, 1)], paths=2000, seed=3, irradiance=True)
        self.assertEqual(r["radiance"].shape, (2, 2))
        self.assertEqual(r["standard_error"].shape, (2, 2))
        self.assertEqual(r["diffuse_horizontal"].shape, (2,))
        self.assertTrue((r["standard_error"] > 0).all() and (r["standard_error"] < 0.2 * r["radiance"]).all())
        j = json.loads(cli("reference", "--wavelengths", "450,650", "--sun-elevation", "15", "--probe", "0,90",
                           "--probe", "90,1", "--paths", "2000", "--seed", "3", "--irradiance", "--format", "json", "-q"))
        for k, probe in enumerate(j["probes"]):
            np.testing.assert_allclose(r["radiance"][k], probe["radiance"], rtol=1e-12, atol=0)
            np.testing.assert_allclose(r["standard_error"][k], probe["standard_error"], rtol=1e-12, atol=0)
        np.testing.assert_allclose(r["diffuse_horizontal"], j["diffuse_horizontal"]["irradiance"], rtol=1e-12, atol=0)

    def test_stokes_equal_the_cli_json(self):
        overrides = {"spectrum.wavelengths_nm": [450, 650], "sun.elevation_deg": 15}
        r = skyspec.monte_carlo(overrides=overrides, probes=[(90, 30)], paths=1000, seed=3, stokes=True)
        self.assertEqual(r["stokes"].shape, (1, 2, 4))
        self.assertEqual(r["stokes_standard_error"].shape, (1, 2, 4))
        self.assertTrue((r["stokes"][..., 3] == 0).all())
        j = json.loads(cli("reference", "--wavelengths", "450,650", "--sun-elevation", "15", "--probe", "90,30",
                           "--paths", "1000", "--seed", "3", "--stokes", "--format", "json", "-q"))
        np.testing.assert_allclose(r["stokes"][0], j["probes"][0]["stokes"], rtol=1e-12, atol=0)

    def test_bad_probe_names_the_argument(self):
        with self.assertRaises(ValueError) as e:
            skyspec.monte_carlo(probes=[(0, 91)], paths=10)
        self.assertIn("probes", str(e.exception))
        with self.assertRaises(ValueError) as e:
            skyspec.monte_carlo(paths=1)
        self.assertIn("paths", str(e.exception))


class IrradianceAgainstCli(unittest.TestCase):
    def test_irradiance_equals_the_cli_csv(self):
        overrides = dict(SMALL_TABLES, **{"spectrum.wavelengths_nm": [400, 450, 550, 650, 700]})
        calls = []
        r = skyspec.irradiance(overrides=overrides, sun_elevations=[12, 40, -3],
                               progress=lambda done, total: calls.append((done, total)))
        self.assertEqual(calls[-1], (3, 3))
        np.testing.assert_array_equal(r["sun_elevation_deg"], [12, 40, -3])
        self.assertEqual(r["global_horizontal_W_m2_nm"].shape, (3, 5))
        import csv
        rows = list(csv.DictReader(cli("irradiance", "--sun-elevations", "12,40,-3", "--format", "csv",
                                       *set_args({k: v for k, v in overrides.items() if k != "spectrum.wavelengths_nm"}),
                                       "--wavelengths", "400,450,550,650,700").splitlines()))
        self.assertEqual(len(rows), 3)
        for k, row in enumerate(rows):
            for key, text in row.items():
                if key in r and key != "sun_elevation_deg":  # the CSV's numbers, rounded to its decimals
                    value = r[key][k]
                    if value is not None and re.fullmatch(r"-?[0-9.]+", text):
                        decimals = len(text.split(".")[1]) if "." in text else 0
                        self.assertAlmostEqual(value, float(text), delta=0.51 * 10 ** -decimals, msg=key)
            # The spectrum integrates (trapezoid over the grid) to the band's number.
            self.assertAlmostEqual(np.trapz(r["global_horizontal_W_m2_nm"][k], r["wavelength_nm"]),
                                   r["global_horizontal_W_m2"][k], delta=1e-9 * max(1.0, r["global_horizontal_W_m2"][k]))
        # The parts add up; the sun below the horizon leaves the diffuse light alone.
        np.testing.assert_allclose(r["global_horizontal_W_m2"], r["direct_horizontal_W_m2"] + r["diffuse_horizontal_W_m2"],
                                   rtol=1e-12)
        self.assertEqual(r["direct_normal_W_m2"][2], 0.0)
        self.assertGreater(r["diffuse_horizontal_W_m2"][2], 0.0)
        self.assertTrue(all(c is None or 1000 < c < 100000 for c in r["global_cct_K"]))
        self.assertNotIn("broadband_global_horizontal_W_m2", r)

    def test_bad_input_names_the_argument_or_key(self):
        for elevations, name in [([95], "sun_elevations"), ([], "sun_elevations"), (["x"], "sun_elevations")]:
            with self.assertRaises(ValueError) as e:
                skyspec.irradiance(sun_elevations=elevations)
            self.assertIn(name, str(e.exception))
        with self.assertRaises(ValueError) as e:
            skyspec.irradiance(overrides={"render.path": "rgb-fast"})
        self.assertIn("render.path", str(e.exception))


class PublishedValues(unittest.TestCase):
    def test_standard_atmosphere_definition(self):
        # U.S. Standard Atmosphere 1976: 288.15 K and 101325 Pa at sea level, 216.65 K from 11 to 20 km
        # geopotential (11.019 to 20.063 km geometric).
        s = skyspec.us_standard_atmosphere(np.array([0.0, 15000.0, 19000.0]))
        np.testing.assert_allclose(s["temperature_K"], [288.15, 216.65, 216.65], rtol=1e-9)
        self.assertAlmostEqual(float(s["pressure_Pa"][0]), 101325.0, places=6)
        np.testing.assert_allclose(s["number_density_per_m3"], s["pressure_Pa"] / (1.380649e-23 * s["temperature_K"]),
                                   rtol=1e-12)

    def test_bodhaine_cross_section(self):
        # Bodhaine et al. 1999: sigma(550 nm) = 4.51e-27 cm^2 at 360 ppm CO2.
        sigma = skyspec.rayleigh_cross_section([550.0], co2_ppm=360)[0]
        self.assertLess(abs(sigma / 4.51e-31 - 1), 1e-3)

    def test_comparisons(self):
        refs = {c["id"]: c for c in skyspec.published_comparisons()}
        self.assertLess(refs["bodhaine1999_table3"]["max_abs_difference_percent"], 0.1)
        self.assertEqual(len(refs["seed_constants"]["published"]), 3)


class OneSchema(unittest.TestCase):
    """overrides= takes exactly the keys of the registry that scene files and --set use."""

    def test_every_key_round_trips_as_an_override(self):
        import tomllib
        keys = skyspec.scene_keys()
        self.assertEqual(len(keys), len(cli("render", "--help-keys").splitlines()))
        default = tomllib.loads(skyspec.scene_toml())
        for key in keys:
            table, _, leaf = key.rpartition(".")
            node = default
            for part in table.split("."):
                node = node[part]
            if leaf not in node:
                continue  # keys with no value in the default scene (e.g. an unset exposure)
            # A key that one camera type reads (its help says which) is set with that camera, and
            # one read only under a condition ("read only with K = V and K2 = V2", the first of
            # "V or V'") with it.
            camera = re.search(r"\) (fisheye|perspective|equirectangular): ", keys[key])
            overrides = {"camera.type": camera.group(1)} if camera else {}
            condition = re.search(r"; read only with (.*)$", keys[key])
            if condition:
                for clause in condition.group(1).split(" and "):
                    k, value = re.fullmatch(r'([\w.]+) = ("[^"]*"|\w+).*', clause).groups()
                    overrides[k] = tomllib.loads("v = " + value)["v"]
            with self.subTest(key=key):
                try:
                    expected = tomllib.loads(skyspec.scene_toml(overrides=overrides))
                except ValueError as e:
                    if "terrain.file" in str(e):
                        continue  # a terrain from a file: test_terrain.sh sets these keys with one
                    raise
                again = tomllib.loads(skyspec.scene_toml(overrides={**overrides, key: node[leaf]}))
                self.assertEqual(again, expected)

    def test_a_key_outside_the_registry_is_refused(self):
        with self.assertRaisesRegex(ValueError, "camera.heigth"):
            skyspec.scene_toml(overrides={"camera.heigth": 8})


class ScalarsAndDefaults(unittest.TestCase):
    """Issue 20: a scalar wherever an array is taken; one CO2 default (the scenes' 420 ppm)."""

    def test_a_scalar_wavelength_or_altitude(self):
        one = skyspec.derive(550, altitudes_m=1000)
        listed = skyspec.derive([550.0], altitudes_m=[1000.0])
        self.assertEqual(one["rayleigh_scattering_per_m"].shape, (1, 1))
        np.testing.assert_array_equal(one["rayleigh_scattering_per_m"], listed["rayleigh_scattering_per_m"])
        # Issue 41: shapes as NumPy keeps them (derive's arrays are tables: (altitudes, wavelengths)).
        self.assertEqual(skyspec.rayleigh_cross_section(550).shape, ())
        grid = skyspec.rayleigh_cross_section([[400, 500], [600, 700]])
        self.assertEqual(grid.shape, (2, 2))
        self.assertEqual(grid[1, 0], skyspec.rayleigh_cross_section(600))
        self.assertEqual(skyspec.us_standard_atmosphere([[0, 1000]])["pressure_Pa"].shape, (1, 2))
        self.assertIn("550", skyspec.coefficient_report("csv", wavelengths_nm=550))

    def test_one_co2_default(self):
        scene_co2 = skyspec.derive(550)["co2_ppm"]
        self.assertEqual(scene_co2, 420.0)
        self.assertEqual(skyspec.rayleigh_cross_section(550), skyspec.rayleigh_cross_section(550, co2_ppm=scene_co2))
        self.assertNotEqual(skyspec.rayleigh_cross_section(550), skyspec.rayleigh_cross_section(550, co2_ppm=360))


class HostileInput(unittest.TestCase):
    """Issue 19: input that once crashed the interpreter or slipped through is a ValueError."""

    def test_deep_toml_is_an_error_not_a_crash(self):
        for text in ["a" + ".a" * 70000 + " = 1", "[" + "a." * 40000 + "a]", "x = " + "[" * 40000 + "]" * 40000]:
            with self.assertRaises(ValueError) as e:
                skyspec.scene_toml(scene_toml=text)
            self.assertIn("scene_toml:1:", str(e.exception))

    def test_a_folder_is_not_a_scene_file(self):
        with self.assertRaises(ValueError) as e:
            skyspec.scene_toml(scene_file=tempfile.gettempdir())
        self.assertIn("this is a folder", str(e.exception))
        self.assertIn("scene_file = ", str(e.exception))  # Python's word for the path, not the CLI's --scene
        self.assertNotIn("--scene", str(e.exception))

    def test_wavelengths_and_altitudes_are_checked(self):
        for bad in [1e300, float("nan"), 100.0, 1700.0]:
            with self.assertRaises(ValueError) as e:
                skyspec.rayleigh_cross_section([550.0, bad])
            self.assertIn("wavelengths_nm", str(e.exception))
            self.assertIn("230 to 1690 nm", str(e.exception))
        # The refractive index's range reaches into the ultraviolet and near infrared.
        uv, nir = skyspec.rayleigh_cross_section([300.0, 1500.0])
        self.assertGreater(uv / nir, 700.0)  # (1500/300)^4 = 625, more as n - 1 and F rise in the UV
        with self.assertRaises(ValueError) as e:
            skyspec.us_standard_atmosphere(None)
        self.assertIn("altitude_m = None", str(e.exception))


class PythonValues(unittest.TestCase):
    """Issue 41: NumPy's integers and booleans are what they are; paths may be pathlib.Path."""

    def test_numpy_integers_and_booleans(self):
        toml = skyspec.scene_toml(overrides={"camera.width": np.int64(8), "camera.height": np.uint16(4),
                                             "render.sky_view_table": np.bool_(False)})
        self.assertIn("width = 8\n", toml)
        self.assertIn("height = 4\n", toml)
        self.assertIn("sky_view_table = false\n", toml)
        with self.assertRaisesRegex(ValueError, r"camera\.width = 8\.5"):  # a float stays a float
            skyspec.scene_toml(overrides={"camera.width": np.float64(8.5)})

    def test_path_like_files(self):
        import pathlib
        with tempfile.TemporaryDirectory() as tmp:
            folder = pathlib.Path(tmp)
            (folder / "scene.toml").write_text("[sun]\nelevation_deg = 7\n")
            self.assertIn("elevation_deg = 7", skyspec.scene_toml(scene_file=folder / "scene.toml"))
            img = skyspec.render(scene_file=folder / "scene.toml",
                                 overrides={"camera.width": 4, "camera.height": 4, "render.scattering_orders": 1})
            img.write_exr(folder / "sky.exr")
            img.write_png(folder / "sky.png")
            self.assertTrue((folder / "sky.exr").stat().st_size > 0 and (folder / "sky.png").stat().st_size > 0)
            with self.assertRaisesRegex(ValueError, r"scene_file.*missing\.toml"):
                skyspec.scene_toml(scene_file=folder / "missing.toml")


class LongCalls(unittest.TestCase):
    """Issues 41 and 42: progress while a call runs, and Ctrl-C that stops it within a second."""

    def test_progress_callback_sees_every_row(self):
        seen = []
        img = skyspec.render(overrides={**SMALL_TABLES, "camera.width": 8, "camera.height": 40},
                             progress=lambda done, total: seen.append((done, total)))
        self.assertEqual(img.spectral.shape[:2], (40, 8))
        self.assertTrue(seen, "the callback was never called")
        self.assertEqual(seen[-1], (40, 40))
        self.assertEqual([d for d, _ in seen], sorted(d for d, _ in seen))
        self.assertTrue(all(t == 40 for _, t in seen))

    def test_an_exception_in_the_callback_stops_the_call(self):
        class Enough(Exception):
            pass

        def give_up(done, total):
            raise Enough(f"{done}/{total}")

        with self.assertRaises(Enough):
            skyspec.render(overrides={**SMALL_TABLES, "camera.width": 8, "camera.height": 40}, progress=give_up)
        # the library's request is forgotten once the call ended: the next call runs
        self.assertEqual(skyspec.render(overrides={**SMALL_TABLES, "camera.width": 2, "camera.height": 2,
                                                   "render.scattering_orders": 1}).spectral.shape[:2], (2, 2))

    def test_no_bar_where_nobody_watches(self):
        # progress=True in a pipe or a log (not a terminal, not a notebook): nothing on stderr.
        done = subprocess.run([sys.executable, "-c",
                               "import skyspec; skyspec.render(overrides={'camera.width': 2, 'camera.height': 2, "
                               "'render.scattering_orders': 1}, progress=True)"],
                              capture_output=True, text=True)
        self.assertEqual((done.returncode, done.stderr), (0, ""))

    def test_a_bad_progress_argument_is_named(self):
        with self.assertRaisesRegex(ValueError, r"progress.*'yes'.*callable"):
            skyspec.render(overrides={"camera.width": 2, "camera.height": 2}, progress="yes")

    def test_ctrl_c_stops_a_table_build_within_a_second(self):
        # Cold scattering-order tables at the default settings take tens of seconds: Ctrl-C once
        # the bar shows them progressing must raise KeyboardInterrupt at once and leave no table
        # file behind.
        import signal
        import time
        # stderr is a pipe here: it says it is a terminal, so that progress=True draws the bar.
        script = ("import sys, skyspec\n"
                  "class Terminal:\n"
                  "    def __init__(self, s): self.s = s\n"
                  "    def write(self, t): return self.s.write(t)\n"
                  "    def flush(self): self.s.flush()\n"
                  "    def isatty(self): return True\n"
                  "sys.stderr = Terminal(sys.stderr)\n"
                  "try:\n"
                  "    skyspec.render(overrides={'camera.width': 16, 'camera.height': 16}, progress=True)\n"
                  "except KeyboardInterrupt as e:\n"
                  "    print('KeyboardInterrupt', e, file=sys.stderr); sys.exit(42)\n"
                  "sys.exit(0)\n")
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, SKYSPEC_CACHE_DIR=cache)
            child = subprocess.Popen([sys.executable, "-c", script], env=env, stderr=subprocess.PIPE)
            os.set_blocking(child.stderr.fileno(), False)
            err = b""
            deadline = time.monotonic() + 60
            # The bar shows the tables' share built (issue 41: not silence): interrupt once it moves.
            while not re.search(rb"building the scattering tables \[#*\.*\] +[1-9][0-9]?%", err) \
                    and time.monotonic() < deadline:
                time.sleep(0.05)
                err += child.stderr.read() or b""
            sent = time.monotonic()
            child.send_signal(signal.SIGINT)
            try:
                child.wait(timeout=10)
            finally:
                child.kill()
            waited = time.monotonic() - sent
            os.set_blocking(child.stderr.fileno(), True)
            err = (err + child.stderr.read()).decode()
            child.stderr.close()
            self.assertEqual(child.returncode, 42, err)
            self.assertLess(waited, 1.5, f"Ctrl-C took {waited:.2f} s to stop the call")
            self.assertEqual(os.listdir(cache), [], "a table file was left behind")



class Spheres(unittest.TestCase):
    """Lorenz-Mie, water and the Lee diagram from Python: the values of the C++ tests' sources."""

    def test_lorenz_mie_water_case_of_wiscombe(self):
        # MIEV0 case 10: m = 1.33 - 1e-5 i (MIEV0's sign), x = 100.
        r = skyspec.lorenz_mie(1.33 + 1e-5j, 100.0, angles_deg=np.array([[0.0, 90.0], [120.0, 180.0]]))
        self.assertAlmostEqual(r["qext"] / 2.101321, 1.0, delta=2e-6)
        self.assertAlmostEqual(r["qsca"] / 2.096594, 1.0, delta=2e-6)
        self.assertEqual(r["s1"].shape, (2, 2))
        self.assertEqual(r["s1"].dtype, np.complex128)
        # The optical theorem: Qext = 4 / x^2 Re S(0).
        self.assertAlmostEqual(4.0 / 100.0**2 * r["s1"][0, 0].real / r["qext"], 1.0, delta=1e-9)
        with self.assertRaisesRegex(ValueError, "angles_deg"):
            skyspec.lorenz_mie(1.33, 10.0, angles_deg=[200.0])

    def test_water_index_check_value_and_shape(self):
        # IAPWS R9-97's check value is at 997.047 kg/m^3 (25 degC); Kell's density there differs by 2.5e-3.
        n = skyspec.water_refractive_index([589.3], temperature_C=25.0)
        self.assertAlmostEqual(n[0], 1.3328581926, delta=2e-6)
        self.assertEqual(skyspec.water_refractive_index(550.0).shape, ())
        with self.assertRaisesRegex(ValueError, "temperature_C"):
            skyspec.water_refractive_index(550.0, temperature_C=-5.0)

    def test_aerosol_optics_reproduce_opac(self):
        # OPAC 3.1's continental polluted mixture at 80 % and 550 nm (test_aerosol_components has the source).
        r = skyspec.aerosol_optics([650.0, 550.0], components={"inso": 0.6, "waso": 15700, "soot": 34300},
                                   relative_humidity_percent=80)
        self.assertEqual(list(r["wavelengths_nm"]), [550.0, 650.0])
        self.assertAlmostEqual(r["extinction_per_m"][0] * 1e3 / 0.1746, 1.0, delta=0.01)
        self.assertAlmostEqual(r["single_scattering_albedo"][0], 0.8925, delta=0.005)
        self.assertAlmostEqual(r["asymmetry"][0], 0.6977, delta=0.005)
        self.assertEqual(r["p11"].shape, (2, r["angles_deg"].size))
        self.assertEqual((r["angles_deg"][0], r["angles_deg"][-1]), (0.0, 180.0))
        # The phase function integrates to 1 over the sphere (linear in mu between the angles).
        mu = np.cos(np.radians(r["angles_deg"]))
        self.assertAlmostEqual(2 * np.pi * -np.trapz(r["p11"][0], mu), 1.0, delta=1e-9)
        with self.assertRaisesRegex(ValueError, "components = \"dust\" is not allowed: OPAC's component names"):
            skyspec.aerosol_optics(550.0, components={"dust": 1.0})
        with self.assertRaisesRegex(ValueError, r"components = \{'waso': 0\} is not allowed: at least one component"):
            skyspec.aerosol_optics(550.0, components={"waso": 0})
        with self.assertRaisesRegex(ValueError, "relative_humidity_percent = 100.0 is not allowed"):
            skyspec.aerosol_optics(550.0, components={"waso": 1.0}, relative_humidity_percent=100)

    def test_lee_diagram_arrays_and_errors(self):
        calls = []
        d = skyspec.lee_diagram(width=40, height=5, lambda_step_nm=50, polarisation=True,
                                progress=lambda done, total: calls.append((done, total)))
        self.assertEqual(d["radiance"].shape, (5, 40, 9))
        self.assertEqual(d["q"].shape, (5, 40, 9))
        self.assertEqual(list(d["radii_um"][[0, -1]]), [1000.0, 10.0])
        self.assertTrue(np.all(np.isfinite(d["radiance"])) and np.all(d["radiance"] > 0))
        self.assertEqual(calls[-1], (5, 5))
        with self.assertRaisesRegex(ValueError, r"radius_max_um = 5000 is not allowed"):
            skyspec.lee_diagram(radius_max_um=5000)

if __name__ == "__main__":
    unittest.main()
