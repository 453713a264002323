"""Type stubs of the `skyspec` module (python/skyspec_module.cpp), installed beside it.

skyspec: a spectral, physically based sky simulator. Scenes are a preset ("default", "seed", ...),
then an optional scene file or TOML text, then `overrides`, a dict of scene keys, flat
({"sun.elevation_deg": 5}) or nested ({"sun": {"elevation_deg": 5}}); every key is in scene_keys()
and docs/scene-keys.md. Bad input raises ValueError naming the key; files, OSError.
tests/python/test_stubs.py checks that these names and parameters are the module's.
"""
import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Numbers = Union[float, Sequence[float], npt.NDArray[np.float64]]
"""A number, or a list/array of numbers (a wavelength in nm, an altitude in m)."""

_PathLike = Union[str, "os.PathLike[str]"]
"""A file's path: a str or a pathlib.Path (any os.PathLike)."""

_Progress = Union[None, bool, Callable[[int, int], Any]]
"""None, True (a bar with an ETA on stderr) or a callable progress(done, total) called as the work advances."""

class RenderResult:
    """A sky rendered into memory, with what it shows (render() makes it).

    Row 0 is the top of the image, as in the EXR; h x w pixels, n wavelengths. spectral and rgb are
    writable views of the result (write_exr / write_png write what they hold); directions and
    wavelengths_nm are read-only views.
    """

    @property
    def spectral(self) -> npt.NDArray[np.float32]:
        """(h, w, n): spectral radiance, W m^-2 sr^-1 nm^-1 (absolute with sun.spectrum = "solar")."""
    @property
    def stokes(self) -> Optional[npt.NDArray[np.float32]]:
        """(h, w, n, 4): [S0, S1, S2, S3] in each pixel's frame with output.polarisation, else None."""
    @property
    def stokes_e1(self) -> Optional[npt.NDArray[np.float64]]:
        """(h, w, 3): e1 of each pixel's Stokes frame (the image's x axis on the sky), else None."""
    @property
    def wavelengths_nm(self) -> npt.NDArray[np.float64]:
        """(n,): the wavelengths, nm."""
    @property
    def xyz(self) -> npt.NDArray[np.float32]:
        """(h, w, 3): CIE 1931 XYZ, Y in cd m^-2."""
    @property
    def rgb(self) -> npt.NDArray[np.float32]:
        """(h, w, 3): linear Rec.709 (D65), the EXR's R, G, B; Y in cd m^-2."""
    @property
    def directions(self) -> npt.NDArray[np.float64]:
        """(h, w, 3): unit view direction through each pixel's centre, east-north-up at the scene's
        reference point (x east, y north, z up); (0, 0, 0) where the camera has none."""
    @property
    def valid(self) -> npt.NDArray[np.bool_]:
        """(h, w): whether the pixel has a view direction (False outside a fisheye's circle)."""
    @property
    def width(self) -> int:
        """Pixels."""
    @property
    def height(self) -> int:
        """Pixels."""
    @property
    def sun_direction(self) -> npt.NDArray[np.float64]:
        """(3,): unit vector towards the sun's centre, in the frame of directions."""
    @property
    def sun_azimuth_deg(self) -> float:
        """The sun's azimuth, degrees clockwise from north (computed for sun.date_time when set)."""
    @property
    def sun_elevation_deg(self) -> float:
        """The sun's elevation above the horizon, degrees."""
    @property
    def exposure_scale(self) -> float:
        """The factor the preview applies to rgb (the EXR's skyspec:exposureScale): output.exposure_ev
        when the scene sets it, else the automatic one (log-average luminance -> 0.18)."""
    @property
    def exposure_ev(self) -> float:
        """log2(exposure_scale)."""
    @property
    def exposure(self) -> str:
        """How the exposure was chosen, in words (the EXR's skyspec:exposure)."""
    @property
    def scene_toml(self) -> str:
        """The effective scene as TOML, every key (the EXR's skyspec:scene)."""
    @property
    def scene(self) -> Dict[str, Any]:
        """The effective scene as a nested dict (scene_toml read with tomllib)."""
    def pixel(self, azimuth_deg: float, elevation_deg: float) -> Tuple[int, int]:
        """(row, column) of the pixel whose view direction is nearest (azimuth clockwise from north,
        elevation), degrees."""
    def spectrum_at(self, azimuth_deg: float, elevation_deg: float) -> npt.NDArray[np.float64]:
        """(n,): the spectral radiance of the pixel nearest that direction, W m^-2 sr^-1 nm^-1."""
    def write_exr(self, path: _PathLike) -> None:
        """Write the spectral EXR as `skyspec render` writes it for this scene (channels, values and
        header), atomically."""
    def write_png(
        self,
        path: _PathLike,
        *,
        display: Optional[str] = None,
        view: Optional[str] = None,
        look: Optional[str] = None,
        bits: int = 8,
        exposure_ev: Optional[float] = None,
        ocio: Optional[str] = None,
    ) -> float:
        """Write the image through an OpenColorIO display and view as a PNG, as `skyspec render`
        writes its preview (default: skyspec's config, sRGB, Un-tone-mapped, 8 bits, the recorded
        exposure), atomically. Returns the exposure's scale."""

def render(
    preset: str = "default",
    *,
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    progress: _Progress = None,
) -> RenderResult:
    """Render a scene into memory; no files are written until you ask (RenderResult.write_exr)."""

def aerial_perspective(
    depth: Any,
    *,
    depth_is: str = "distance",
    preset: str = "default",
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    progress: _Progress = None,
) -> Dict[str, Any]:
    """Aerial perspective for a (height, width) depth pass in metres (depth_is="z": along the view
    axis): transmittance and inscatter (h, w, n), their RGB (h, w, 3), wavelengths_nm, scene_toml."""

def timelapse(
    start: str,
    end: str,
    step_minutes: float,
    *,
    preset: str = "default",
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    out: Optional[_PathLike] = None,
    name: Optional[str] = None,
    frames: Optional[str] = None,
    resume: bool = False,
    force: bool = False,
    progress: _Progress = None,
) -> Dict[str, Any]:
    """A time-lapse: one image per step_minutes from start to end (ISO 8601 with a UTC offset) at the
    scene's location, one exposure for every frame; files <name>_0000.exr/.png with records and
    manifest.jsonl in out. Returns frames, written, kept, failed, exposure_ev, files, manifest, ..."""

def irradiance(
    preset: str = "default",
    *,
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    sun_elevations: Optional[Sequence[float]] = None,
    progress: _Progress = None,
) -> Dict[str, Any]:
    """The irradiance at the camera (`skyspec irradiance`) for each sun elevation: arrays named as the
    irradiance tables' columns (direct_normal_W_m2, global_horizontal_lux, ..., spectra *_W_m2_nm),
    wavelength_nm, sun_elevation_deg and the colour temperatures. docs/python.md."""

def monte_carlo(
    preset: str = "default",
    *,
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    probes: Optional[Sequence[Sequence[float]]] = None,
    paths: int = 100000,
    seed: int = 1,
    orders: int = 0,
    irradiance: bool = False,
    stokes: bool = False,
    sun_peak_share: float = 0.0,
    progress: _Progress = None,
) -> Dict[str, Any]:
    """The Monte Carlo reference (all scattering orders) at (azimuth_deg, elevation_deg) probes:
    radiance and standard_error arrays (probes x wavelengths), optionally the diffuse horizontal
    irradiance and the Stokes vectors (stokes, stokes_standard_error: probes x wavelengths x 4).
    docs/validation.md."""

def run_job(
    job: str,
    *,
    out: Optional[str] = None,
    scheduler: Optional[str] = None,
    workers: Optional[int] = None,
    threads: int = 1,
    skyspec: Optional[str] = None,
    quiet: bool = False,
) -> Dict[str, Any]:
    """Run a job file on Dask (a LocalCluster, or `scheduler`); returns the summary dict, raises
    skyspec_jobs.JobFailed when tasks failed or did not run. docs/jobs.md."""

def derive(
    wavelengths_nm: Optional[_Numbers] = None,
    *,
    preset: str = "default",
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    altitudes_m: _Numbers = 0.0,
    pressure_Pa: Optional[float] = None,
    temperature_K: Optional[float] = None,
    latitude_deg: float = 45.0,
    refractive_index: Optional[str] = None,
    co2_ppm: Optional[float] = None,
) -> Dict[str, Any]:
    """The scattering coefficients of a scene's atmosphere per wavelength, from n(lambda) and N: a
    dict of NumPy arrays (shapes (n,), (k,) or (k, n) for n wavelengths and k altitudes) and the
    strings refractive_index, rayleigh_source and the float co2_ppm. help(skyspec.derive) lists the keys.
    Wavelengths 230-1690 nm; the ozone arrays hold NaN beyond the built-in ozone table (230-1060 nm)."""

def coefficient_report(
    format: str = "md",
    *,
    wavelengths_nm: Optional[_Numbers] = None,
    preset: str = "default",
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
    altitudes_m: _Numbers = 0.0,
    pressure_Pa: Optional[float] = None,
    temperature_K: Optional[float] = None,
    latitude_deg: float = 45.0,
    refractive_index: Optional[str] = None,
    co2_ppm: Optional[float] = None,
) -> str:
    """The coefficient derivation report as text: format "md", "csv", "json" or "html" (the output of
    `skyspec coefficients`); the other arguments are derive()'s."""

def published_comparisons() -> List[Dict[str, Any]]:
    """skyspec's derivation against published values at the published conditions."""

def us_standard_atmosphere(altitude_m: _Numbers) -> Dict[str, npt.NDArray[np.float64]]:
    """U.S. Standard Atmosphere 1976 at geometric altitudes (m, -5 km to 100 km): temperature_K,
    pressure_Pa and number_density_per_m3, shaped like altitude_m."""

def rayleigh_cross_section(
    wavelengths_nm: _Numbers, refractive_index: str = "peck-reeder", co2_ppm: Optional[float] = None
) -> npt.NDArray[np.float64]:
    """Rayleigh cross-section of dry air per molecule, m^2 (Bodhaine et al. 1999 eq. 2), 230-1690 nm (the refractive index formula's range);
    shaped like wavelengths_nm (a number gives shape ()); co2_ppm defaults to the scenes' 420 ppm."""

def lorenz_mie(m: complex, x: float, *, angles_deg: Optional[_Numbers] = None) -> Dict[str, Any]:
    """One homogeneous sphere by Lorenz-Mie theory (Wiscombe's algorithm): m the relative refractive index
    (imaginary part >= 0 absorbs), x = 2 pi r n_medium / lambda (1e-3 to 2e4): qext, qsca, qabs, qback, g,
    terms; with angles_deg (degrees) also s1, s2 (complex) and s11, s12, s33, s34, shaped like angles_deg."""

def aerosol_optics(
    wavelengths_nm: _Numbers,
    *,
    components: Dict[str, float],
    relative_humidity_percent: float = 70.0,
    progress: _Progress = None,
) -> Dict[str, npt.NDArray[np.float64]]:
    """An aerosol from its microphysics, as atmosphere.mie.model = "opac" computes it: OPAC's components by
    Lorenz-Mie theory. components: OPAC's name -> particles per cm^3 (inso, waso, soot, ssam, sscm, minm, miam,
    micm, mitr, suso); 250-2500 nm. Returns wavelengths_nm, extinction_per_m, scattering_per_m,
    single_scattering_albedo, asymmetry, angles_deg (0-180) and p11 (sr^-1), p12, p33, p34 [wavelength, angle]."""

def water_refractive_index(wavelengths_nm: _Numbers, *, temperature_C: float = 10.0) -> npt.NDArray[np.float64]:
    """The refractive index of liquid water (IAPWS R9-97), 200-1100 nm, 0-100 degC; shaped like wavelengths_nm."""

def lee_diagram(
    *,
    radius_min_um: float = 10.0,
    radius_max_um: float = 1000.0,
    angle_min_deg: float = 125.0,
    angle_max_deg: float = 145.0,
    width: int = 400,
    height: int = 100,
    lambda_min_nm: float = 380.0,
    lambda_max_nm: float = 780.0,
    lambda_step_nm: float = 10.0,
    water_temperature_C: float = 10.0,
    angle_samples: int = 4,
    polarisation: bool = False,
    progress: _Progress = None,
) -> Dict[str, npt.NDArray[Any]]:
    """The Lee diagram (`skyspec lee-diagram`): radiance (height, width, wavelengths; E_sun P_11 per unit
    scattering optical depth, row 0 the largest radius), wavelengths_nm, angles_deg, radii_um and, with
    polarisation, q (positive when polarised perpendicular to the scattering plane)."""

def scene_toml(
    preset: str = "default",
    *,
    scene_file: Optional[_PathLike] = None,
    scene_toml: Optional[str] = None,
    overrides: Optional[Dict[str, Any]] = None,
) -> str:
    """The effective scene as TOML text, every key."""

def scene_keys() -> Dict[str, str]:
    """Every scene key that overrides= accepts, with its unit, allowed range and meaning."""

def preset_names() -> List[str]:
    """Names of the built-in scene presets."""
