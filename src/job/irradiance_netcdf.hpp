// A site's irradiance series as NetCDF with CF conventions (CF-1.8, a discrete-sampling-geometry
// time series of one station), the form atmospheric scientists open with xarray or ncdump: the same
// rows as irradiance_<site>.csv (job_collect.hpp). Written in the classic 64-bit-offset format,
// whose bytes depend on the values alone (no HDF5 time stamps): the same job gives the same file.
//
//   dimensions  time (or sample, when the job sweeps parameters), wavelength
//   variables   time (seconds since 1970-01-01 UTC), wavelength (nm), lat, lon, altitude,
//               station_name (cf_role timeseries_id), solar_elevation_angle, solar_azimuth_angle,
//               the swept parameters (their scene keys as names), broadband irradiance (W m-2)
//               and illuminance (lx), spectral global / diffuse horizontal and direct normal
//               irradiance (W m-2 nm-1)
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <vector>

#include "job/job_plan.hpp"

namespace skyspec {

/// Writes `rows` (task records with "irradiance", all of one site, in task order) atomically.
/// Throws IoError naming the file when NetCDF cannot write it.
void write_irradiance_netcdf(const std::filesystem::path& path, const JobPlan& plan, int site,
                             const std::vector<const nlohmann::json*>& rows);

}  // namespace skyspec
