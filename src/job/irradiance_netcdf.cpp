#include "job/irradiance_netcdf.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "base/atomic_file.hpp"
#include "base/dynamic_library.hpp"
#include "base/text_format.hpp"
#include "physics/date_time.hpp"
#include "render/irradiance.hpp"
#include "scene/key_registry.hpp"
#include "skyspec/error.hpp"
#include "skyspec/version.hpp"

namespace skyspec {
namespace {

using nlohmann::json;

// netCDF's C functions, looked up once in the library opened on first use
// (base/dynamic_library.hpp): only a job's collection, which writes NetCDF, loads it.
// clang-format off
#define SKYSPEC_NETCDF_FUNCTIONS(X)                                                                         \
  X(nc_create) X(nc_close) X(nc_strerror) X(nc_def_dim) X(nc_def_var) X(nc_put_att_text) X(nc_put_var_double) \
  X(nc_put_var_text) X(nc_enddef)
// clang-format on
SKYSPEC_SHARED_LIBRARY_API(NetcdfApi, netcdf, SKYSPEC_NETCDF_FUNCTIONS, SKYSPEC_NETCDF_SONAME,
                           "writing NetCDF irradiance tables (netCDF)")

class NcFile {
 public:
  explicit NcFile(const std::filesystem::path& path) : path_(path) {
    check(netcdf().nc_create(path.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, &id_), "create");
  }
  ~NcFile() {
    if (id_ >= 0) netcdf().nc_close(id_);
  }
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  int id() const { return id_; }
  void check(int status, const char* what) const {
    if (status != NC_NOERR)
      throw IoError("NetCDF '" + path_.string() + "': cannot " + what + ": " + netcdf().nc_strerror(status));
  }
  int dim(const std::string& name, size_t length) {
    int d = -1;
    check(netcdf().nc_def_dim(id_, name.c_str(), length, &d), "define a dimension");
    return d;
  }
  int var(const std::string& name, nc_type type, std::vector<int> dims) {
    int v = -1;
    check(netcdf().nc_def_var(id_, name.c_str(), type, static_cast<int>(dims.size()), dims.data(), &v),
          "define a variable");
    return v;
  }
  void text(int var, const char* name, const std::string& value) {
    check(netcdf().nc_put_att_text(id_, var, name, value.size(), value.c_str()), "write an attribute");
  }
  void put(int var, const std::vector<double>& values) {
    check(netcdf().nc_put_var_double(id_, var, values.data()), "write a variable");
  }
  void close() { check(netcdf().nc_close(std::exchange(id_, -1)), "close"); }

 private:
  std::filesystem::path path_;
  int id_ = -1;
};

// A scene key's unit (as docs/scene-keys.md writes it) in UDUNITS, or none where UDUNITS has no
// such unit (the Dobson unit): then the long name carries it.
std::optional<std::string> udunits(const std::string& unit) {
  if (unit.empty()) return "1";
  if (unit == "degrees") return "degree";
  if (unit == "ppm") return "1e-6";
  if (unit == "Dobson units") return std::nullopt;
  std::string u = unit;  // "m^-1" -> "m-1", "W m^-2 nm^-1" -> "W m-2 nm-1"
  u.erase(std::remove(u.begin(), u.end(), '^'), u.end());
  return u;
}

// "ground.albedo" -> "ground_albedo": CF's variable names are letters, digits and underscores.
std::string variable_name_of_key(std::string key) {
  std::replace(key.begin(), key.end(), '.', '_');
  return key;
}

double unix_seconds(const std::string& iso) {
  DateTime epoch;
  epoch.year = 1970;
  return seconds_between(epoch, parse_iso8601(iso, "date_time"));
}

}  // namespace

void write_irradiance_netcdf(const std::filesystem::path& path, const JobPlan& plan, int site,
                             const std::vector<const json*>& rows) {
  if (rows.empty()) return;
  // One wavelength axis for the file: every row's grid must be the first's (records are validated
  // per task by record_problem; a job that sweeps spectrum keys gives rows of other grids).
  const auto& first_wl = rows.front()->at("irradiance").at("wavelengths_nm");
  for (const json* row : rows)
    if (row->at("irradiance").at("wavelengths_nm") != first_wl)
      throw IoError("task " + row->value("id", std::string("?")) + " has other wavelengths than task " +
                    rows.front()->value("id", std::string("?")) + ": one irradiance NetCDF holds one wavelength grid");
  AtomicOutputFile file(path);
  {
    NcFile nc(file.temporary_path());
    const JobParameters& params = plan.combinations.front();
    const bool timed = !plan.job.times.empty();
    const std::string sample = params.empty() && timed ? "time" : "sample";
    const auto& wl = rows.front()->at("irradiance").at("wavelengths_nm");
    const int d_sample = nc.dim(sample, rows.size());
    const int d_wl = nc.dim("wavelength", wl.size());
    const std::string station = site < 0 ? std::string("scene") : plan.job.sites[site].name;
    const int d_name = nc.dim("name_strlen", station.size());
    const std::string coords = std::string(timed && sample != "time" ? "time " : "") + "lat lon altitude station_name";

    const int g = NC_GLOBAL;
    nc.text(g, "Conventions", "CF-1.8");
    nc.text(g, "featureType", "timeSeries");
    nc.text(g, "title", "skyspec irradiance at " + station + " (job " + plan.job.name + ")");
    nc.text(g, "source", std::string("skyspec ") + version_string() + ": spectral single and multiple scattering");
    nc.text(g, "references", "docs/jobs.md; docs/physics.md (irradiance at the camera)");
    if (!params.empty()) {
      std::string keys;
      for (const auto& [key, value] : params) keys += (keys.empty() ? "" : " ") + key;
      nc.text(g, "skyspec_swept_parameters", keys);
    }

    int v_time = -1;
    if (timed) {
      v_time = nc.var("time", NC_DOUBLE, {d_sample});
      nc.text(v_time, "standard_name", "time");
      nc.text(v_time, "units", "seconds since 1970-01-01 00:00:00 UTC");
      nc.text(v_time, "calendar", "standard");
    }
    const int v_wl = nc.var("wavelength", NC_DOUBLE, {d_wl});
    nc.text(v_wl, "standard_name", "radiation_wavelength");
    nc.text(v_wl, "units", "nm");
    const int v_lat = nc.var("lat", NC_DOUBLE, {}), v_lon = nc.var("lon", NC_DOUBLE, {}),
              v_alt = nc.var("altitude", NC_DOUBLE, {});
    nc.text(v_lat, "standard_name", "latitude");
    nc.text(v_lat, "units", "degrees_north");
    nc.text(v_lon, "standard_name", "longitude");
    nc.text(v_lon, "units", "degrees_east");
    nc.text(v_alt, "standard_name", "altitude");
    nc.text(v_alt, "units", "m");
    nc.text(v_alt, "long_name", "height of the measuring point above sea level");
    const int v_name = nc.var("station_name", NC_CHAR, {d_name});
    nc.text(v_name, "cf_role", "timeseries_id");
    nc.text(v_name, "long_name", "site");
    nc.text(v_name, "_Encoding", "utf-8");  // read as text, not bytes (netCDF4-python, xarray)
    // The band every W m-2 value integrates over: the render's wavelengths (not the whole solar
    // spectrum a pyranometer sees; docs/jobs.md, "Irradiance and pyranometers").
    const double band_min = wl.front().get<double>(), band_max = wl.back().get<double>();
    const std::string band_comment = "integral over " + format_number(band_min) + "-" + format_number(band_max) +
                                     " nm only (the render's wavelengths, trapezoid rule): not the whole solar "
                                     "spectrum a pyranometer measures (docs/jobs.md)";
    nc.text(g, "skyspec_band_nm", format_number(band_min) + " " + format_number(band_max));

    struct Series {
      int var;
      std::vector<double> values;
    };
    // Standard names only where the CF table has one for exactly this quantity; units in UDUNITS.
    const auto series = [&](const std::string& name, const char* standard_name, const std::string& long_name,
                            const char* units, bool spectral) {
      Series s{nc.var(name, NC_DOUBLE, spectral ? std::vector<int>{d_sample, d_wl} : std::vector<int>{d_sample}), {}};
      if (standard_name) nc.text(s.var, "standard_name", standard_name);
      nc.text(s.var, "long_name", long_name);
      if (units) nc.text(s.var, "units", units);
      nc.text(s.var, "coordinates", coords);
      return s;
    };
    Series elevation = series("solar_elevation_angle", "solar_elevation_angle", "apparent solar elevation (refracted)",
                              "degree", false);
    Series azimuth =
        series("solar_azimuth_angle", "solar_azimuth_angle", "solar azimuth, clockwise from north", "degree", false);
    // A swept key: a variable named as CF names variables (letters, digits, underscores), its
    // scene key in an attribute, its unit in UDUNITS where it has one; strings as NaN.
    std::vector<Series> swept;
    for (const auto& [key, value] : params) {
      const scene_keys::KeyDef* def = scene_keys::find_key(key);
      const std::optional<std::string> units = def && !def->text ? udunits(def->unit) : std::nullopt;
      std::string long_name = "scene key " + key + " (swept)";
      if (def && !def->text && !units) long_name += ", in " + def->unit;
      swept.push_back(series(variable_name_of_key(key), nullptr, long_name, units ? units->c_str() : nullptr, false));
      nc.text(swept.back().var, "skyspec_scene_key", key);
    }
    // No CF standard name for the band-limited irradiance: surface_*_shortwave_flux_in_air means
    // the whole solar spectrum.
    // The broadband values (300-4000 nm, the whole solar spectrum but 2 %) have them, when the
    // first row has them (a row without them: NaN).
    std::vector<Series> data;
    std::vector<const IrradianceQuantity*> quantities;
    const json& first_irradiance = rows.front()->at("irradiance");
    for (const IrradianceQuantity& q : irradiance_quantities()) {
      if (q.of_broadband && !first_irradiance.contains(q.key)) continue;
      quantities.push_back(&q);
      data.push_back(series(q.variable, q.standard_name, q.long_name, q.units, q.spectral()));
      if (q.band_limited()) nc.text(data.back().var, "comment", band_comment);
      if (q.of_broadband)
        nc.text(data.back().var, "comment",
                "300-4000 nm (trapezoid over Bird & Riordan's 122 wavelengths), all scattering orders, with the "
                "absorption bands of water vapour and the mixed gases (docs/jobs.md, \"Irradiance and pyranometers\")");
    }
    nc.check(netcdf().nc_enddef(nc.id()), "end the definitions");

    std::vector<double> times;
    for (const json* r : rows) {
      if (timed) times.push_back(unix_seconds(r->at("date_time").get<std::string>()));
      elevation.values.push_back(r->at("sun_elevation_deg").get<double>());
      azimuth.values.push_back(r->at("sun_azimuth_deg").get<double>());
      for (std::size_t p = 0; p < params.size(); ++p) {
        const json& v = r->at("parameters").at(params[p].first);
        swept[p].values.push_back(v.is_number()    ? v.get<double>()
                                  : v.is_boolean() ? (v.get<bool>() ? 1.0 : 0.0)
                                                   : std::numeric_limits<double>::quiet_NaN());
      }
      const json& irr = r->at("irradiance");
      for (std::size_t k = 0; k < data.size(); ++k) {
        const IrradianceQuantity& q = *quantities[k];
        if (q.of_broadband && !irr.contains(q.key))
          data[k].values.push_back(std::numeric_limits<double>::quiet_NaN());
        else if (q.spectral())
          for (const auto& v : irr.at(q.key)) data[k].values.push_back(v.get<double>());
        else
          data[k].values.push_back(irr.at(q.key).get<double>());
      }
    }
    if (timed) nc.put(v_time, times);
    nc.put(v_wl, wl.get<std::vector<double>>());
    // Where the irradiance is: the first row's scene (the site, or the scene's own location).
    const Scene where = task_scene(plan, plan.tasks.at(rows.front()->at("task").get<std::size_t>()));
    nc.put(v_lat, {where.location.latitude_deg});
    nc.put(v_lon, {where.location.longitude_deg});
    nc.put(v_alt, {where.camera.position_m.z()});
    nc.check(netcdf().nc_put_var_text(nc.id(), v_name, station.c_str()), "write a variable");
    nc.put(elevation.var, elevation.values);
    nc.put(azimuth.var, azimuth.values);
    for (const auto& s : swept) nc.put(s.var, s.values);
    for (const auto& s : data) nc.put(s.var, s.values);
    nc.close();
  }
  file.commit();
}

}  // namespace skyspec
