#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "io/elevation_raster.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_elevation_raster)

using namespace skyspec;
using skyspec::test::ScratchFolder;

namespace {
constexpr double R = 6371e3;
constexpr double kPeakLat = 46.25, kPeakLon = 7.30;

// A cone 3000 m high and 10 km in radius on a 500 m plateau, its apex at (kPeakLat, kPeakLon);
// distances on the sphere of radius R (great circles).
double cone(double lat_deg, double lon_deg) {
  const double p1 = degrees_to_radians(lat_deg), p2 = degrees_to_radians(kPeakLat);
  const double dl = degrees_to_radians(lon_deg - kPeakLon);
  const double c = std::sin(p1) * std::sin(p2) + std::cos(p1) * std::cos(p2) * std::cos(dl);
  const double d = R * std::acos(std::min(1.0, c));
  return 500.0 + 3000.0 * std::max(0.0, 1.0 - d / 10000.0);
}

// Writes a GeoTIFF with the GDAL API: width x height pixels, the geotransform gt, the CRS of the
// EPSG code (0: none), heights from height(x, y) at each pixel centre in the raster's coordinates.
void write_geotiff(const std::string& path, int width, int height, const double* gt, int epsg,
                   const std::function<double(double, double)>& height_at, double nodata = NAN) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  BOOST_REQUIRE(driver);
  std::unique_ptr<GDALDataset> ds(driver->Create(path.c_str(), width, height, 1, GDT_Float32, nullptr));
  BOOST_REQUIRE(ds);
  if (gt) ds->SetGeoTransform(const_cast<double*>(gt));
  if (epsg) {
    OGRSpatialReference srs;
    srs.importFromEPSG(epsg);
    ds->SetSpatialRef(&srs);
  }
  std::vector<float> v(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double px = gt ? gt[0] + (x + 0.5) * gt[1] : x, py = gt ? gt[3] + (y + 0.5) * gt[5] : y;
      v[static_cast<size_t>(y) * width + x] = static_cast<float>(height_at(px, py));
    }
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (!std::isnan(nodata)) band->SetNoDataValue(nodata);
  BOOST_REQUIRE(band->RasterIO(GF_Write, 0, 0, width, height, v.data(), width, height, GDT_Float32, 0, 0, nullptr) ==
                CE_None);
}

// Latitude/longitude raster over 46.0-46.5 N, 7.0-7.5 E, 0.001 degree pixels.
const double kGeographic[6] = {7.0, 0.001, 0.0, 46.5, 0.0, -0.001};

ElevationSampling around_reference(double extent_m, double spacing_m) {
  ElevationSampling s;
  s.latitude_deg = 46.25;
  s.longitude_deg = 7.25;
  s.extent_m = extent_m;
  s.spacing_m = spacing_m;
  s.planet_radius_m = R;
  return s;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

BOOST_AUTO_TEST_CASE(geographic_geotiff_heights_land_where_they_belong) {
  const ScratchFolder dir("dem");
  const std::string path = (dir.path / "cone.tif").string();
  write_geotiff(path, 500, 500, kGeographic, 4326, [](double lon, double lat) { return cone(lat, lon); });
  const ElevationSampling s = around_reference(15000.0, 50.0);
  const HeightGrid g = read_elevation_raster(path, s);
  BOOST_TEST(g.columns == 601);
  BOOST_TEST(g.east0_m == -15000.0);
  // Every sample is the cone at its own latitude and longitude, to the raster's interpolation.
  double worst = 0.0;
  int peak = 0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      double lat = 0.0, lon = 0.0;
      map_to_latitude_longitude(g.east_m(c), g.north_m(r), s, lat, lon);
      const double want = cone(lat, lon);
      // On the flank, away from the kinks at the apex and the foot (where bilinear interpolation of
      // 77 x 111 m pixels is off by up to slope x pixel / 4, 8 m).
      if (want > 600.0 && want < 3200.0) worst = std::max(worst, std::abs(g.at(c, r) - want));
      if (g.at(c, r) > g.at(peak % g.columns, peak / g.columns)) peak = r * g.columns + c;
    }
  BOOST_TEST(worst < 1.0);
  // The apex: 0.05 degrees of longitude east at 46.25 N, 3.849 km on the sphere.
  const double east = g.east_m(peak % g.columns), north = g.north_m(peak / g.columns);
  BOOST_TEST(std::abs(east - R * degrees_to_radians(0.05) * std::cos(degrees_to_radians(46.25))) < 60.0);
  BOOST_TEST(std::abs(north) < 60.0);
  BOOST_TEST(g.at(peak % g.columns, peak / g.columns) > 3400.0f);
  // The grid makes a terrain whose surface is the cone.
  const Terrain t(g, R);
  BOOST_TEST(t.max_height_m() > 3400.0);
}

// The same cone in UTM zone 32N (metres): the transform from latitude and longitude into the
// raster's coordinates puts the apex in the same place.
BOOST_AUTO_TEST_CASE(projected_geotiff_is_transformed) {
  const ScratchFolder dir("dem");
  const std::string path = (dir.path / "cone-utm.tif").string();
  OGRSpatialReference geographic, utm;
  geographic.SetWellKnownGeogCS("WGS84");
  geographic.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  utm.importFromEPSG(32632);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_geo(OGRCreateCoordinateTransformation(&utm, &geographic));
  BOOST_REQUIRE(to_geo);
  // Around the apex (UTM 32N: about 369.6 km E, 5123.3 km N), 100 m pixels.
  const double gt[6] = {350000.0, 100.0, 0.0, 5145000.0, 0.0, -100.0};
  write_geotiff(path, 400, 400, gt, 32632, [&](double x, double y) {
    double lon = x, lat = y;
    to_geo->Transform(1, &lon, &lat);
    return cone(lat, lon);
  });
  const ElevationSampling s = around_reference(12000.0, 100.0);
  const HeightGrid g = read_elevation_raster(path, s);
  int peak = 0;
  for (int i = 0; i < g.columns * g.rows; ++i)
    if (g.height_m[static_cast<size_t>(i)] > g.height_m[static_cast<size_t>(peak)]) peak = i;
  const double east = g.east_m(peak % g.columns), north = g.north_m(peak / g.columns);
  BOOST_TEST(std::abs(east - 3849.0) < 150.0);
  BOOST_TEST(std::abs(north) < 150.0);
  BOOST_TEST(g.height_m[static_cast<size_t>(peak)] > 3300.0f);
}

BOOST_AUTO_TEST_CASE(unusable_rasters_are_refused_naming_the_file) {
  const ScratchFolder dir("dem");
  const ElevationSampling s = around_reference(10000.0, 100.0);
  auto flat = [](double, double) { return 800.0; };
  // Not a raster at all.
  const std::string text = (dir.path / "notes.tif").string();
  skyspec::test::write_text(dir.path / "notes.tif", "not a raster\n");
  std::string m = message_of([&] { read_elevation_raster(text, s); });
  BOOST_TEST(m.find("terrain.file") != std::string::npos, m);
  BOOST_TEST(m.find("notes.tif") != std::string::npos, m);
  // No georeferencing.
  const std::string bare = (dir.path / "bare.tif").string();
  write_geotiff(bare, 50, 50, nullptr, 0, flat);
  m = message_of([&] { read_elevation_raster(bare, s); });
  BOOST_TEST(m.find("georeferenced") != std::string::npos, m);
  BOOST_TEST(m.find("bare.tif") != std::string::npos, m);
  // Does not cover the square around the location.
  const std::string small = (dir.path / "small.tif").string();
  const double gt_small[6] = {7.24, 0.001, 0.0, 46.26, 0.0, -0.001};
  write_geotiff(small, 20, 20, gt_small, 4326, flat);
  m = message_of([&] { read_elevation_raster(small, s); });
  BOOST_TEST(m.find("covers") != std::string::npos, m);
  // Absurd heights.
  const std::string tall = (dir.path / "tall.tif").string();
  write_geotiff(tall, 500, 500, kGeographic, 4326, [](double, double) { return 20000.0; });
  m = message_of([&] { read_elevation_raster(tall, s); });
  BOOST_TEST(m.find("9000") != std::string::npos, m);
  // A hole without data.
  const std::string holes = (dir.path / "holes.tif").string();
  write_geotiff(
      holes, 500, 500, kGeographic, 4326,
      [](double lon, double lat) {
        return std::abs(lon - 7.25) < 0.01 && std::abs(lat - 46.25) < 0.01 ? -9999.0 : 800.0;
      },
      -9999.0);
  m = message_of([&] { read_elevation_raster(holes, s); });
  BOOST_TEST(m.find("no data") != std::string::npos, m);
}

BOOST_AUTO_TEST_SUITE_END()
