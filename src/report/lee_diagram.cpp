#include "skyspec/lee_diagram.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/cancellation.hpp"
#include "base/output_lock.hpp"
#include "base/text_format.hpp"
#include "colour/display_pipeline.hpp"
#include "io/png_image.hpp"
#include "io/spectral_exr.hpp"
#include "physics/solar_spectrum.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/lorenz_mie.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"
#include "skyspec/water.hpp"

namespace skyspec {

namespace {

void require(bool ok, const char* setting, double value, const std::string& allowed) {
  if (!ok) throw InputError(setting, format_number(value), allowed);
}

// The refractive index of standard air (15 degC, 101325 Pa), the drops' surroundings.
double air_index(double lambda_nm) {
  return 1.0 + refractivity_standard_air(RefractiveIndexFormula::PeckReeder1972, lambda_nm);
}

WavelengthGrid lee_grid(const LeeDiagramSettings& s) {
  return WavelengthGrid::uniform(s.lambda_min_nm, s.lambda_max_nm, s.lambda_step_nm);
}

std::string describe(const LeeDiagramSettings& s) {
  std::ostringstream d;
  d << "Lee diagram: L = E_sun P_11 of water drops (W m^-2 sr^-1 nm^-1 per unit scattering optical depth); "
    << "columns: scattering angle " << s.angle_min_deg << "-" << s.angle_max_deg
    << " deg, left to right; rows: drop radius " << s.radius_max_um << "-" << s.radius_min_um
    << " um, top to bottom, logarithmic; water at " << s.water_temperature_C << " degC (IAPWS R9-97) in standard air; "
    << s.angle_subsamples << " angles averaged per column";
  return d.str();
}
}  // namespace

void check_lee_diagram_settings(const LeeDiagramSettings& s) {
  namespace k = lee_setting;
  require(s.width >= 1 && s.width <= 8192, k::kWidth, s.width, "a whole number from 1 to 8192");
  require(s.height >= 1 && s.height <= 4096, k::kHeight, s.height, "a whole number from 1 to 4096");
  require(s.angle_subsamples >= 1 && s.angle_subsamples <= 64, k::kSubsamples, s.angle_subsamples,
          "a whole number from 1 to 64");
  require(s.angle_min_deg >= 0.0 && s.angle_min_deg < 180.0, k::kAngleMin, s.angle_min_deg, "0 <= angle < 180 degrees");
  require(s.angle_max_deg > s.angle_min_deg && s.angle_max_deg <= 180.0, k::kAngleMax, s.angle_max_deg,
          "above " + format_number(s.angle_min_deg) + " (" + k::kAngleMin + ") and at most 180 degrees");
  require(s.lambda_min_nm >= 280.0 && s.lambda_min_nm <= 1100.0, k::kLambdaMin, s.lambda_min_nm,
          "280-1100 nm (the solar spectrum's table from 280 nm, water's index to 1100 nm)");
  require(s.lambda_max_nm >= s.lambda_min_nm && s.lambda_max_nm <= 1100.0, k::kLambdaMax, s.lambda_max_nm,
          "from " + format_number(s.lambda_min_nm) + " (" + k::kLambdaMin + ") to 1100 nm");
  try {
    lee_grid(s);
  } catch (const InputError&) {
    throw InputError(k::kLambdaStep, format_number(s.lambda_step_nm),
                     "a step of at least 1 nm that divides " + std::string(k::kLambdaMax) + " - " + k::kLambdaMin +
                         " evenly, at most 1024 wavelengths");
  }
  require(s.water_temperature_C >= 0.0 && s.water_temperature_C <= 100.0, k::kTemperature, s.water_temperature_C,
          "0-100 degC (liquid water at atmospheric pressure)");
  require(s.radius_min_um > 0.0 && std::isfinite(s.radius_min_um), k::kRadiusMin, s.radius_min_um, "a positive radius");
  // The largest drop at the shortest wavelength must stay within the solver's size parameter.
  const double largest_um = 2e4 * s.lambda_min_nm * 1e-3 / (2.0 * kPi * air_index(s.lambda_min_nm));
  require(s.radius_max_um >= s.radius_min_um && s.radius_max_um <= largest_um, k::kRadiusMax, s.radius_max_um,
          "from " + format_number(s.radius_min_um) + " (" + k::kRadiusMin + ") to " +
              format_number(std::floor(largest_um)) + " um (size parameter 2e4 at " + format_number(s.lambda_min_nm) +
              " nm)");
  const double pixels = static_cast<double>(s.width) * s.height;
  require(pixels * lee_grid(s).size() <= 2e8, k::kWidth, s.width,
          "width x height x wavelengths at most 2e8 (" + format_number(pixels * lee_grid(s).size()) + " asked)");
}

LeeDiagram compute_lee_diagram(const LeeDiagramSettings& s, const std::function<void(int, int)>& progress) {
  check_lee_diagram_settings(s);
  LeeDiagram d;
  d.settings = s;
  d.width = s.width;
  d.height = s.height;
  const WavelengthGrid grid = lee_grid(s);
  const int n = grid.size();
  d.wavelengths_nm = grid.nanometres();
  const SpectrumD sun = solar_irradiance_on_grid(grid, lee_setting::kLambdaMin);
  const double temperature_K = s.water_temperature_C + 273.15;
  const double density = liquid_water_density_kg_per_m3(temperature_K);
  const double column = (s.angle_max_deg - s.angle_min_deg) / s.width;
  std::vector<double> mu;  // every column's subsamples, column-major
  for (int x = 0; x < s.width; ++x) {
    d.angles_deg.push_back(s.angle_min_deg + (x + 0.5) * column);
    for (int k = 0; k < s.angle_subsamples; ++k)
      mu.push_back(std::cos((s.angle_min_deg + (x + (k + 0.5) / s.angle_subsamples) * column) * kPi / 180.0));
  }
  for (int y = 0; y < s.height; ++y)
    d.radii_um.push_back(s.height == 1 ? s.radius_max_um
                                       : s.radius_max_um * std::pow(s.radius_min_um / s.radius_max_um,
                                                                    static_cast<double>(y) / (s.height - 1)));
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  d.spectral.assign(pixels * n, 0.0f);
  if (s.polarisation) d.stokes.assign(pixels * 3 * n, 0.0f);
  // Rows in blocks, each (row, wavelength) a task; progress between blocks, on this thread.
  constexpr int kBlock = 4;
  for (int first = 0; first < s.height; first += kBlock) {
    const int rows = std::min(kBlock, s.height - first);
    tbb::parallel_for(0, rows * n, [&](int task) {
      throw_if_cancelled();
      const int y = first + task / n, i = task % n;
      const double lambda_nm = grid.nm(i), n_air = air_index(lambda_nm);
      const std::complex<double> m(water_refractive_index(temperature_K, density, lambda_nm) / n_air, 0.0);
      const double x = 2.0 * kPi * d.radii_um[static_cast<size_t>(y)] * 1e3 * n_air / lambda_nm;  // um over nm
      const MieSeries series = lorenz_mie(m, x);
      // P_ij = S_ij / (k^2 C_sca) = S_ij / (pi x^2 Q_sca): per unit solid angle, integrating to 1.
      const double scale = sun[i] / (kPi * x * x * mie_efficiencies(series).scattering) / s.angle_subsamples;
      const std::vector<MieAmplitudes> amp = mie_amplitudes(series, mu);
      for (int c = 0; c < s.width; ++c) {
        double s11 = 0.0, s12 = 0.0;
        for (int k = 0; k < s.angle_subsamples; ++k) {
          const SphereScatteringMatrix m4 =
              sphere_scattering_matrix(amp[static_cast<size_t>(c * s.angle_subsamples + k)]);
          s11 += m4.s11;
          s12 += m4.s12;
        }
        const size_t p = static_cast<size_t>(y) * s.width + c;
        d.spectral[p * n + i] = static_cast<float>(scale * s11);
        if (s.polarisation) d.stokes[(p * 3) * n + i] = static_cast<float>(-scale * s12);
      }
    });
    if (progress) progress(first + rows, s.height);
  }
  return d;
}

LeeDiagramFiles write_lee_diagram(const LeeDiagram& d, const std::filesystem::path& dir, const std::string& name,
                                  const DisplaySettings& display, bool png) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw InputError(lee_setting::kName, "\"" + name + "\"", "a file name without '/'");
  const DisplayPipeline pipeline(display);  // checks the display's names before any file is written
  const OutputFolderGuard folder(dir, lee_setting::kDirectory);
  const OutputLock lock(dir, name, lee_setting::kName);  // one writer per name
  const int n = static_cast<int>(d.wavelengths_nm.size());
  const size_t pixels = static_cast<size_t>(d.width) * d.height;
  // Linear Rec.709 of every pixel (Y in cd m^-2 per unit optical depth).
  const SpectrumToXyz to_xyz(WavelengthGrid::from_list(d.wavelengths_nm), constants::kMaxLuminousEfficacy_lm_per_W);
  const Eigen::Matrix3d to_rgb = xyz_to_linear_rec709();
  std::vector<float> rgb(pixels * 3);
  std::vector<double> luminance(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    const SpectrumD spectrum = Eigen::Map<const Spectrum>(&d.spectral[p * n], n).cast<double>();
    const Eigen::Vector3d xyz = to_xyz(spectrum);
    const Eigen::Vector3d c = to_rgb * xyz;
    for (int k = 0; k < 3; ++k) rgb[p * 3 + k] = static_cast<float>(c[k]);
    luminance[p] = xyz[1];
  }
  LeeDiagramFiles out;
  SpectralExrMetadata meta;
  meta.strings["skyspec:content"] = describe(d.settings);
  meta.strings["skyspec:version"] = version_string();
  meta.polarised = !d.stokes.empty();
  out.exr = dir / (name + ".exr");
  {
    SpectralExrWriter writer(out.exr, d.width, d.height, d.wavelengths_nm, meta);
    if (meta.polarised) {
      std::vector<float> all(pixels * 4 * n);
      for (size_t p = 0; p < pixels; ++p) {
        std::copy_n(&d.spectral[p * n], n, &all[p * 4 * n]);
        std::copy_n(&d.stokes[p * 3 * n], 3 * n, &all[p * 4 * n + n]);
      }
      writer.write_rows(d.height, all.data(), rgb.data());
    } else {
      writer.write_rows(d.height, d.spectral.data(), rgb.data());
    }
    writer.finish();
  }
  if (!png) return out;
  try {
    // Each row scaled so that its brightest pixel has luminance 1, then the display transform.
    std::vector<float> scaled = rgb;
    for (int y = 0; y < d.height; ++y) {
      const auto row = luminance.begin() + static_cast<std::ptrdiff_t>(y) * d.width;
      const double peak = *std::max_element(row, row + d.width);
      const double f = peak > 0.0 ? 1.0 / peak : 0.0;
      for (size_t v = static_cast<size_t>(y) * d.width * 3; v < static_cast<size_t>(y + 1) * d.width * 3; ++v)
        scaled[v] = static_cast<float>(scaled[v] * f);
    }
    out.png = dir / (name + ".png");
    write_png_display(
        out.png, d.width, d.height, pipeline.encode(std::move(scaled), 1.0), display.png_bit_depth, pipeline.png_tag(),
        {{"Software", std::string("skyspec ") + version_string()}, {"Description", describe(d.settings)}});
  } catch (...) {  // the pair or nothing: a failed PNG takes its EXR with it, as a failed render's files do
    std::error_code ec;
    std::filesystem::remove(out.exr, ec);
    throw;
  }
  return out;
}

}  // namespace skyspec
