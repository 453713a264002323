#include "io/elevation_raster.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <vector>

#include <ImfChannelList.h>

#include <cpl_error.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_srs_api.h>

#include "base/dynamic_library.hpp"
#include "base/text_format.hpp"
#include "io/exr_channels.hpp"
#include "io/exr_open.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
constexpr double kLowest_m = -500.0, kHighest_m = 9000.0;  // the Dead Sea's shore, Everest
constexpr double kMaxWindowPixels = 2.0e8;

// GDAL's C functions, looked up once in the library opened on first use (base/dynamic_library.hpp):
// a process that reads no raster does not load GDAL and the libraries it brings.
// clang-format off
#define SKYSPEC_GDAL_FUNCTIONS(X)                                                                         \
  X(GDALAllRegister) X(GDALOpenEx) X(GDALClose) X(GDALGetRasterCount) X(GDALGetSpatialRef)                \
  X(GDALGetGeoTransform) X(GDALInvGeoTransform) X(GDALGetRasterBand) X(GDALGetRasterUnitType)             \
  X(GDALGetRasterScale) X(GDALGetRasterOffset) X(GDALGetRasterNoDataValue) X(GDALGetRasterXSize)          \
  X(GDALGetRasterYSize) X(GDALRasterIO) X(GDALGetRasterDataType) X(OSRNewSpatialReference)                \
  X(OSRSetWellKnownGeogCS) X(OSRSetAxisMappingStrategy) X(OSRClone) X(OSRDestroySpatialReference)         \
  X(OCTNewCoordinateTransformation) X(OCTTransform) X(OCTDestroyCoordinateTransformation)                 \
  X(CPLPushErrorHandler) X(CPLQuietErrorHandler) X(CPLErrorReset) X(CPLPopErrorHandler) X(CPLGetLastErrorMsg)
// clang-format on
SKYSPEC_SHARED_LIBRARY_API(GdalApi, gdal_functions, SKYSPEC_GDAL_FUNCTIONS, SKYSPEC_GDAL_SONAME,
                           "reading elevation and albedo rasters (GDAL)")

// GDAL, with its drivers (GeoTIFF, PNG, ...) registered once.
const GdalApi& gdal() {
  static const bool registered = (gdal_functions().GDALAllRegister(), true);
  static_cast<void>(registered);
  return gdal_functions();
}

// GDAL's own messages are kept for ours, not printed.
struct QuietGdal {
  QuietGdal() {
    gdal().CPLPushErrorHandler(gdal().CPLQuietErrorHandler);
    gdal().CPLErrorReset();
  }
  ~QuietGdal() { gdal().CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
  static std::string last() {
    const char* m = gdal().CPLGetLastErrorMsg();
    return m && *m ? std::string(" (GDAL: ") + m + ")" : std::string();
  }
};

// A dataset, a spatial reference and a transformation, closed or destroyed at the end of scope.
struct CloseDataset {
  void operator()(void* h) const { gdal().GDALClose(static_cast<GDALDatasetH>(h)); }
};
using Dataset = std::unique_ptr<void, CloseDataset>;
struct DestroyReference {
  void operator()(void* h) const { gdal().OSRDestroySpatialReference(static_cast<OGRSpatialReferenceH>(h)); }
};
using SpatialReference = std::unique_ptr<void, DestroyReference>;
struct DestroyTransformation {
  void operator()(void* h) const {
    gdal().OCTDestroyCoordinateTransformation(static_cast<OGRCoordinateTransformationH>(h));
  }
};
using Transformation = std::unique_ptr<void, DestroyTransformation>;

Dataset open_raster(const std::string& path) {
  return Dataset(gdal().GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
}
}  // namespace

void map_to_latitude_longitude(double east_m, double north_m, const ElevationSampling& s, double& latitude_deg,
                               double& longitude_deg) {
  const double lat = degrees_to_radians(s.latitude_deg), lon = degrees_to_radians(s.longitude_deg);
  // The map point's direction in the reference point's east-north-up frame, then in the planet's
  // frame (x towards latitude 0 longitude 0, z towards the north pole).
  const double len = std::sqrt(east_m * east_m + north_m * north_m + s.planet_radius_m * s.planet_radius_m);
  const double e = east_m / len, n = north_m / len, u = s.planet_radius_m / len;
  const double x = -std::sin(lon) * e - std::sin(lat) * std::cos(lon) * n + std::cos(lat) * std::cos(lon) * u;
  const double y = std::cos(lon) * e - std::sin(lat) * std::sin(lon) * n + std::cos(lat) * std::sin(lon) * u;
  const double z = std::cos(lat) * n + std::sin(lat) * u;
  latitude_deg = radians_to_degrees(std::asin(std::clamp(z, -1.0, 1.0)));
  longitude_deg = radians_to_degrees(std::atan2(y, x));
}

namespace {
// What a raster's values are and which are allowed (after the raster's scale and offset).
struct ValueRule {
  const char* what;  // in messages
  double lowest, highest;
  const char* unit;
  bool heights;  // heights: a DEM's unit converts to metres; below 0 raised to 0
};
constexpr ValueRule kHeights{"heights", kLowest_m, kHighest_m, " m", true};
constexpr ValueRule kAlbedoFactors{"albedo factors", 0.0, 1.0, "", false};

// The value kept for a sample, or a refusal naming the pixel near which it lies.
template <class Refuse>
float accepted(double value, const ValueRule& rule, int ix, int iy, const Refuse& refuse) {
  if (!(value >= rule.lowest && value <= rule.highest))
    refuse(std::string(rule.what) + " between " + format_number(rule.lowest) + " and " + format_number(rule.highest) +
           rule.unit + " (near pixel " + std::to_string(ix) + ", " + std::to_string(iy) + " it is " +
           format_number(value) + rule.unit + ")");
  return static_cast<float>(rule.heights ? std::max(0.0, value) : value);
}

// The map grid of ElevationSampling: centred on the reference point, square.
HeightGrid map_grid(const ElevationSampling& s) {
  if (!(s.spacing_m > 0.0) || !(s.extent_m >= s.spacing_m))
    throw InputError("terrain.extent_m", format_number(s.extent_m),
                     "at least terrain.spacing_m (" + format_number(s.spacing_m) + " m)");
  HeightGrid g;
  const int half = static_cast<int>(std::ceil(s.extent_m / s.spacing_m - 1e-9));
  g.columns = g.rows = 2 * half + 1;
  g.spacing_m = s.spacing_m;
  g.east0_m = g.north0_m = -half * s.spacing_m;
  if (static_cast<double>(g.columns) * static_cast<double>(g.rows) > 1e8)
    throw InputError(
        "terrain.spacing_m", format_number(s.spacing_m),
        "a spacing that gives at most 1e8 samples over terrain.extent_m = " + format_number(s.extent_m) + " m");
  return g;
}

// A georeferenced raster's first band at each sample of the grid (its latitude and longitude).
std::vector<float> sample_georeferenced(const std::string& path, const HeightGrid& g, const ElevationSampling& s,
                                        const std::string& setting, const ValueRule& rule) {
  auto refuse = [&](const std::string& what) { throw InputError(setting, path, what); };
  const GdalApi& g_ = gdal();
  const QuietGdal quiet;
  const Dataset ds = open_raster(path);
  if (!ds)
    refuse(std::string(rule.heights ? "an elevation raster" : "an albedo raster") +
           " GDAL can open (GeoTIFF or another raster format)" + QuietGdal::last());
  if (g_.GDALGetRasterCount(ds.get()) < 1) refuse("a raster with at least one band");
  double gt[6];
  const OGRSpatialReferenceH srs = g_.GDALGetSpatialRef(ds.get());
  if (g_.GDALGetGeoTransform(ds.get(), gt) != CE_None || !srs)
    refuse("a georeferenced raster (a geotransform and a coordinate reference system); this one has " +
           std::string(srs ? "no geotransform" : "no coordinate reference system"));
  double inv[6];
  if (!g_.GDALInvGeoTransform(gt, inv)) refuse("a geotransform that can be inverted");
  const GDALRasterBandH band = g_.GDALGetRasterBand(ds.get(), 1);
  const char* unit_type = g_.GDALGetRasterUnitType(band);
  const std::string unit = unit_type ? unit_type : "";
  double to_m = 1.0;
  if (!rule.heights)
    ;  // an albedo has no unit; whatever the band says
  else if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "US survey foot")
    to_m = unit == "US survey foot" ? 1200.0 / 3937.0 : 0.3048;
  else if (!(unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters"))
    refuse("heights in metres or feet (band 1's unit is \"" + unit + "\")");
  int has_scale = 0, has_offset = 0, has_nodata = 0;
  double scale = g_.GDALGetRasterScale(band, &has_scale), offset = g_.GDALGetRasterOffset(band, &has_offset);
  if (!has_scale) scale = 1.0;
  if (!has_offset) offset = 0.0;
  const double nodata = g_.GDALGetRasterNoDataValue(band, &has_nodata);

  const size_t count = static_cast<size_t>(g.columns) * static_cast<size_t>(g.rows);
  // Each sample's latitude and longitude, into the raster's coordinates, into its pixels.
  std::vector<double> px(count), py(count);
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      const size_t i = static_cast<size_t>(r) * g.columns + c;
      map_to_latitude_longitude(g.east_m(c), g.north_m(r), s, py[i], px[i]);  // lat into y, lon into x
    }
  const SpatialReference geographic(g_.OSRNewSpatialReference(nullptr));
  if (!geographic || g_.OSRSetWellKnownGeogCS(geographic.get(), "WGS84") != OGRERR_NONE)
    refuse("GDAL with the WGS84 coordinate reference system (PROJ's data)" + QuietGdal::last());
  g_.OSRSetAxisMappingStrategy(geographic.get(), OAMS_TRADITIONAL_GIS_ORDER);  // longitude, latitude
  const SpatialReference target(g_.OSRClone(srs));
  if (!target) refuse("a coordinate reference system GDAL can copy" + QuietGdal::last());
  g_.OSRSetAxisMappingStrategy(target.get(), OAMS_TRADITIONAL_GIS_ORDER);
  const Transformation to_raster(g_.OCTNewCoordinateTransformation(geographic.get(), target.get()));
  if (!to_raster)
    refuse("a coordinate reference system PROJ can transform latitude and longitude into" + QuietGdal::last());
  if (!g_.OCTTransform(static_cast<OGRCoordinateTransformationH>(to_raster.get()), static_cast<int>(count), px.data(),
                       py.data(), nullptr))
    refuse("a raster whose coordinates hold the square of half-size terrain.extent_m around the location" +
           QuietGdal::last());
  const int width = g_.GDALGetRasterXSize(ds.get()), height = g_.GDALGetRasterYSize(ds.get());
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x, lo_y = lo_x, hi_y = -lo_x;
  for (size_t i = 0; i < count; ++i) {
    const double x = px[i], y = py[i];
    // Pixel centres are at half-integer pixel coordinates (GDAL's corner convention).
    px[i] = inv[0] + inv[1] * x + inv[2] * y - 0.5;
    py[i] = inv[3] + inv[4] * x + inv[5] * y - 0.5;
    if (!(px[i] >= -0.5 && py[i] >= -0.5 && px[i] <= width - 0.5 && py[i] <= height - 0.5)) {
      double lat = 0.0, lon = 0.0;
      map_to_latitude_longitude(g.east_m(static_cast<int>(i % g.columns)), g.north_m(static_cast<int>(i / g.columns)),
                                s, lat, lon);
      refuse("a raster that covers the square of half-size terrain.extent_m = " + format_number(s.extent_m) +
             " m around the location; latitude " + format_number(lat) + ", longitude " + format_number(lon) +
             " lies outside it");
    }
    lo_x = std::min(lo_x, px[i]);
    hi_x = std::max(hi_x, px[i]);
    lo_y = std::min(lo_y, py[i]);
    hi_y = std::max(hi_y, py[i]);
  }
  // Read the window that holds every sample's four neighbours.
  const int x0 = std::clamp(static_cast<int>(std::floor(lo_x)), 0, width - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(lo_y)), 0, height - 1);
  const int x1 = std::clamp(static_cast<int>(std::floor(hi_x)) + 1, 0, width - 1);
  const int y1 = std::clamp(static_cast<int>(std::floor(hi_y)) + 1, 0, height - 1);
  const int ww = x1 - x0 + 1, wh = y1 - y0 + 1;
  if (static_cast<double>(ww) * wh > kMaxWindowPixels)
    refuse("a raster window of at most 2e8 pixels over terrain.extent_m (this needs " + std::to_string(ww) + " x " +
           std::to_string(wh) + "; make terrain.extent_m smaller)");
  std::vector<double> window(static_cast<size_t>(ww) * static_cast<size_t>(wh));
  if (g_.GDALRasterIO(band, GF_Read, x0, y0, ww, wh, window.data(), ww, wh, GDT_Float64, 0, 0) != CE_None)
    refuse("a raster GDAL can read" + QuietGdal::last());
  auto at = [&](int x, int y) {
    x = std::clamp(x, 0, width - 1) - x0;
    y = std::clamp(y, 0, height - 1) - y0;
    return window[static_cast<size_t>(y) * ww + x];
  };
  std::vector<float> values(count);
  for (size_t i = 0; i < count; ++i) {
    const int ix = static_cast<int>(std::floor(px[i])), iy = static_cast<int>(std::floor(py[i]));
    const double fx = px[i] - ix, fy = py[i] - iy;
    const double v[4] = {at(ix, iy), at(ix + 1, iy), at(ix, iy + 1), at(ix + 1, iy + 1)};
    for (double value : v)
      if ((has_nodata && value == nodata) || !std::isfinite(value))
        refuse(std::string(rule.what) + " everywhere in the square of half-size terrain.extent_m (a cell near pixel " +
               std::to_string(ix) + ", " + std::to_string(iy) + " has no data)");
    const double raw = (1.0 - fy) * ((1.0 - fx) * v[0] + fx * v[1]) + fy * ((1.0 - fx) * v[2] + fx * v[3]);
    values[i] = accepted((raw * scale + offset) * to_m, rule, ix, iy, refuse);
  }
  return values;
}
}  // namespace

HeightGrid read_elevation_raster(const std::string& path, const ElevationSampling& s, const std::string& setting) {
  HeightGrid g = map_grid(s);
  g.height_m = sample_georeferenced(path, g, s, setting, kHeights);
  return g;
}

std::vector<float> read_georeferenced_albedo_map(const std::string& path, const HeightGrid& grid,
                                                 const ElevationSampling& s, const std::string& setting) {
  return sample_georeferenced(path, grid, s, setting, kAlbedoFactors);
}

namespace {
// A height map's values, top row first, each already times its type's scale (1 / 255, 1 / 65535
// for unsigned 8- and 16-bit images, else 1).
struct HeightImage {
  int width = 0, height = 0;
  std::vector<double> value;
};

constexpr double kMaxHeightMapPixels = 1e8;

bool has_exr_extension(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr";
}

template <class Refuse>
void check_height_map_size(long long width, long long height, const Refuse& refuse) {
  if (width < 2 || height < 2 || static_cast<double>(width) * static_cast<double>(height) > kMaxHeightMapPixels)
    refuse("an image of at least 2 x 2 and at most 1e8 pixels (this one is " + std::to_string(width) + " x " +
           std::to_string(height) + ")");
}

template <class Refuse>
HeightImage read_exr_height_image(const std::string& path, const Refuse& refuse, bool pixels) {
  std::string channel;
  long long width = 0, height = 0;
  try {
    const auto file = open_exr_input(path);
    const Imath::Box2i dw = file->header().dataWindow();
    width = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    height = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    std::vector<std::string> names;
    for (auto it = file->header().channels().begin(); it != file->header().channels().end(); ++it)
      names.emplace_back(it.name());
    for (const char* wanted : {"Y", "Z", "R"})
      if (channel.empty() && std::find(names.begin(), names.end(), wanted) != names.end()) channel = wanted;
    if (channel.empty() && names.size() == 1) channel = names.front();
    if (channel.empty()) {
      std::string have;
      for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
      refuse("an OpenEXR image with a channel Y, Z or R, or a single channel (this one has: " + have + ")");
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    refuse(std::string("an OpenEXR file skyspec can read (") + e.what() + ")");
  }
  check_height_map_size(width, height, refuse);
  HeightImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  if (!pixels) return image;
  try {
    const ExrChannels read = read_exr_channels(path, {channel});
    const std::vector<float>& v = read.channels.at(channel);
    image.value.assign(v.begin(), v.end());
  } catch (const std::exception& e) {
    refuse(std::string("an OpenEXR file skyspec can read (") + e.what() + ")");
  }
  return image;
}

template <class Refuse>
HeightImage read_gdal_height_image(const std::string& path, const Refuse& refuse, bool pixels) {
  const GdalApi& g_ = gdal();
  const QuietGdal quiet;
  const Dataset ds = open_raster(path);
  if (!ds) refuse("an image OpenEXR or GDAL can open (EXR, PNG, TIFF, ...)" + QuietGdal::last());
  if (g_.GDALGetRasterCount(ds.get()) < 1) refuse("an image with at least one band");
  check_height_map_size(g_.GDALGetRasterXSize(ds.get()), g_.GDALGetRasterYSize(ds.get()), refuse);
  const GDALRasterBandH band = g_.GDALGetRasterBand(ds.get(), 1);
  HeightImage image;
  image.width = g_.GDALGetRasterXSize(ds.get());
  image.height = g_.GDALGetRasterYSize(ds.get());
  if (!pixels) return image;
  image.value.resize(static_cast<size_t>(image.width) * static_cast<size_t>(image.height));
  if (g_.GDALRasterIO(band, GF_Read, 0, 0, image.width, image.height, image.value.data(), image.width, image.height,
                      GDT_Float64, 0, 0) != CE_None)
    refuse("an image GDAL can read" + QuietGdal::last());
  int has_nodata = 0;
  const double nodata = g_.GDALGetRasterNoDataValue(band, &has_nodata);
  const GDALDataType type = g_.GDALGetRasterDataType(band);
  const double unit = type == GDT_Byte ? 1.0 / 255.0 : type == GDT_UInt16 ? 1.0 / 65535.0 : 1.0;
  for (size_t i = 0; i < image.value.size(); ++i) {
    if (has_nodata && image.value[i] == nodata)
      refuse("a value everywhere (pixel " + std::to_string(i % image.width) + ", " + std::to_string(i / image.width) +
             " holds the no-data value)");
    image.value[i] *= unit;
  }
  return image;
}
template <class Refuse>
HeightImage read_height_image(const std::string& path, const Refuse& refuse, bool pixels) {
  return has_exr_extension(path) ? read_exr_height_image(path, refuse, pixels)
                                 : read_gdal_height_image(path, refuse, pixels);
}

// The image's values (times scale, plus offset) interpolated bilinearly at each sample of the
// grid, the image centred on the reference point with pixel centres pixel_east_m and
// pixel_north_m apart, its top row north.
template <class Refuse>
std::vector<float> sample_image(const HeightImage& image, const HeightGrid& g, double pixel_east_m,
                                double pixel_north_m, double scale, double offset, const ValueRule& rule,
                                const Refuse& refuse) {
  const double centre_x = 0.5 * (image.width - 1), centre_y = 0.5 * (image.height - 1);
  const auto at = [&](int x, int y) {
    x = std::clamp(x, 0, image.width - 1);
    y = std::clamp(y, 0, image.height - 1);
    return image.value[static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x)];
  };
  std::vector<float> values(static_cast<size_t>(g.columns) * static_cast<size_t>(g.rows));
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      const double px = centre_x + g.east_m(c) / pixel_east_m, py = centre_y - g.north_m(r) / pixel_north_m;
      const int ix = static_cast<int>(std::floor(px)), iy = static_cast<int>(std::floor(py));
      const double fx = px - ix, fy = py - iy;
      const double v[4] = {at(ix, iy), at(ix + 1, iy), at(ix, iy + 1), at(ix + 1, iy + 1)};
      for (double value : v)
        if (!std::isfinite(value))
          refuse("finite values (near pixel " + std::to_string(ix) + ", " + std::to_string(iy) + " one is not)");
      const double raw = (1.0 - fy) * ((1.0 - fx) * v[0] + fx * v[1]) + fy * ((1.0 - fx) * v[2] + fx * v[3]);
      values[static_cast<size_t>(r) * static_cast<size_t>(g.columns) + static_cast<size_t>(c)] =
          accepted(raw * scale + offset, rule, ix, iy, refuse);
    }
  return values;
}
}  // namespace

HeightGrid read_height_map(const std::string& path, const HeightMapSampling& s, const std::string& setting) {
  auto refuse = [&](const std::string& what) { throw InputError(setting, path, what); };
  if (!(s.pixel_m > 0.0))
    throw InputError("terrain.heightmap.pixel_m", format_number(s.pixel_m),
                     "the distance between the height map's pixel centres on the ground, in metres (> 0)");
  if (!(s.spacing_m > 0.0) || !(s.extent_m >= s.spacing_m))
    throw InputError("terrain.extent_m", format_number(s.extent_m),
                     "at least terrain.spacing_m (" + format_number(s.spacing_m) + " m)");
  const HeightImage image = read_height_image(path, refuse, true);
  // The grid, centred on the image's centre, as far as the image and extent_m reach.
  const double centre_x = 0.5 * (image.width - 1), centre_y = 0.5 * (image.height - 1);
  const int half_columns =
      static_cast<int>(std::floor(std::min(s.extent_m, centre_x * s.pixel_m) / s.spacing_m + 1e-9));
  const int half_rows = static_cast<int>(std::floor(std::min(s.extent_m, centre_y * s.pixel_m) / s.spacing_m + 1e-9));
  if (half_columns < 1 || half_rows < 1)
    throw InputError("terrain.spacing_m", format_number(s.spacing_m),
                     "at most half the height map's size on the ground (" +
                         format_number(std::min(centre_x, centre_y) * s.pixel_m) + " m)");
  HeightGrid g;
  g.columns = 2 * half_columns + 1;
  g.rows = 2 * half_rows + 1;
  g.spacing_m = s.spacing_m;
  g.east0_m = -half_columns * s.spacing_m;
  g.north0_m = -half_rows * s.spacing_m;
  if (static_cast<double>(g.columns) * g.rows > 1e8)
    throw InputError("terrain.spacing_m", format_number(s.spacing_m),
                     "a spacing that gives at most 1e8 samples over the height map");
  g.height_m = sample_image(image, g, s.pixel_m, s.pixel_m, s.height_scale_m, s.height_offset_m, kHeights, refuse);
  return g;
}

void height_map_pixels(const std::string& path, int& width, int& height, const std::string& setting) {
  auto refuse = [&](const std::string& what) { throw InputError(setting, path, what); };
  const HeightImage image = read_height_image(path, refuse, false);
  width = image.width;
  height = image.height;
}

std::vector<float> read_albedo_image(const std::string& path, const HeightGrid& grid, double width_m, double height_m,
                                     const std::string& setting) {
  auto refuse = [&](const std::string& what) { throw InputError(setting, path, what); };
  const HeightImage image = read_height_image(path, refuse, true);
  return sample_image(image, grid, width_m / image.width, height_m / image.height, 1.0, 0.0, kAlbedoFactors, refuse);
}

}  // namespace skyspec
