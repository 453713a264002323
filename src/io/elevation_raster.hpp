// Elevation rasters (digital elevation models) through GDAL: GeoTIFF and every raster format GDAL
// reads, with their georeferencing (a geotransform and a coordinate reference system); height
// maps, images without georeferencing whose scale the scene states (OpenEXR, PNG, ...); and
// albedo maps read either way onto the same grid.
#pragma once

#include <string>
#include <vector>

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

/// How a height map (an image without georeferencing) lies on the map and what its values mean:
/// its pixel centres are pixel_m apart in the map, the image's centre on the reference point, its
/// top row north and its columns west to east; a value v is the height v x height_scale_m +
/// height_offset_m, where v is the stored value for floating-point and signed-integer images and
/// the code over its largest (255, 65535) for 8- and 16-bit unsigned images (a PNG's codes are 0
/// to 1). The terrain's grid (spacing_m) is sampled from it over at most extent_m from the centre
/// in each direction, and no further than the image reaches.
struct HeightMapSampling {
  double pixel_m = 0.0;
  double height_scale_m = 1.0, height_offset_m = 0.0;
  double extent_m = 30000.0, spacing_m = 100.0;
};

/// The height map's values, bilinearly interpolated at each sample of the terrain's grid: OpenEXR
/// files (.exr; the channel Y, Z or R, or the only channel) through OpenEXR, every other image
/// GDAL reads (PNG, TIFF, ...) through GDAL (band 1; any georeferencing is ignored). Heights below
/// 0 are raised to it. Throws InputError naming `setting` and the file when it cannot be read, has
/// no channel to take, is smaller than 2 x 2 pixels or larger than 1e8, holds a value that is not
/// finite (or GDAL's no-data value), or gives a height outside -500 to 9000 m.
HeightGrid read_height_map(const std::string& path, const HeightMapSampling& sampling,
                           const std::string& setting = "terrain.file");

/// A height map's size in pixels (width, height), from its header. Throws as read_height_map.
void height_map_pixels(const std::string& path, int& width, int& height, const std::string& setting = "terrain.file");

/// An albedo map on the samples of `grid` (one factor per sample, row-major like its heights), each
/// in [0, 1]. Georeferenced (terrain.model = file): the raster's first band at each sample's
/// latitude and longitude, as read_elevation_raster reads heights (its scale and offset applied,
/// its unit ignored). Over a height map (heightmap): an image read as read_height_map reads one
/// (8- and 16-bit codes over their largest), spread over the ground of width_m x height_m the
/// height map covers, centred on the reference point, top row north. Throws InputError naming
/// `setting` and the file as the readers of heights do, and for a factor outside [0, 1].
std::vector<float> read_georeferenced_albedo_map(const std::string& path, const HeightGrid& grid,
                                                 const ElevationSampling& sampling,
                                                 const std::string& setting = "terrain.albedo_map");
std::vector<float> read_albedo_image(const std::string& path, const HeightGrid& grid, double width_m, double height_m,
                                     const std::string& setting = "terrain.albedo_map");

/// The latitude and longitude (degrees) of the point of the sphere at map coordinates (east,
/// north) around the reference point: the inverse of the gnomonic projection.
void map_to_latitude_longitude(double east_m, double north_m, const ElevationSampling& sampling, double& latitude_deg,
                               double& longitude_deg);

}  // namespace skyspec
