// Elevation rasters (digital elevation models) through GDAL: GeoTIFF and every raster format GDAL
// reads, with their georeferencing (a geotransform and a coordinate reference system).
#pragma once

#include <string>

#include "skyspec/terrain.hpp"

namespace skyspec {

/// Where and how finely to sample a raster: the square of half-size extent_m (in the terrain's
/// map, terrain.hpp) around the reference point at latitude_deg / longitude_deg on a sphere of
/// radius planet_radius_m, every spacing_m.
struct ElevationSampling {
  double latitude_deg = 0.0, longitude_deg = 0.0;
  double extent_m = 30000.0, spacing_m = 100.0;
  double planet_radius_m = 6371e3;
};

/// The raster's first band, bilinearly interpolated at each sample of the map grid (each sample's
/// latitude and longitude on the sphere, transformed into the raster's own coordinate reference
/// system). Heights below sea level are raised to it (the sphere is height 0). Throws InputError
/// naming `setting` (the scene key, terrain.file) and the file when GDAL cannot open it, it has no
/// georeferencing, its heights are not in metres or feet, it does not cover the square, a sample
/// falls on a cell without data, or a height is absurd (below -500 m or above 9000 m).
HeightGrid read_elevation_raster(const std::string& path, const ElevationSampling& sampling,
                                 const std::string& setting = "terrain.file");

/// The latitude and longitude (degrees) of the point of the sphere at map coordinates (east,
/// north) around the reference point: the inverse of the gnomonic projection.
void map_to_latitude_longitude(double east_m, double north_m, const ElevationSampling& sampling, double& latitude_deg,
                               double& longitude_deg);

}  // namespace skyspec
