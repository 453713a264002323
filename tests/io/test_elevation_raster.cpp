#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "io/elevation_raster.hpp"
#include "io/exr_channels.hpp"
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

namespace {
// Writes a single-band image with GDAL (MEM, then CreateCopy: PNG's driver only copies): width x
// height pixels of type `type`, code(x, y) at column x, row y (row 0 on top), no georeferencing.
void write_gdal_image(const std::string& path, const char* driver_name, GDALDataType type, int width, int height,
                      const std::function<double(int, int)>& code) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  BOOST_REQUIRE(mem && driver);
  std::unique_ptr<GDALDataset> ds(mem->Create("", width, height, 1, type, nullptr));
  BOOST_REQUIRE(ds);
  std::vector<double> v(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) v[static_cast<size_t>(y) * width + x] = code(x, y);
  BOOST_REQUIRE(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, v.data(), width, height, GDT_Float64, 0,
                                               0, nullptr) == CE_None);
  std::unique_ptr<GDALDataset> out(driver->CreateCopy(path.c_str(), ds.get(), TRUE, nullptr, nullptr, nullptr));
  BOOST_REQUIRE(out);
}

HeightMapSampling height_map(double pixel_m, double scale_m, double extent_m, double spacing_m) {
  HeightMapSampling s;
  s.pixel_m = pixel_m;
  s.height_scale_m = scale_m;
  s.extent_m = extent_m;
  s.spacing_m = spacing_m;
  return s;
}
}  // namespace

// A 16-bit PNG: its codes over 65535 times the scale, the image's centre on the reference point,
// its top row north and its columns eastwards.
BOOST_AUTO_TEST_CASE(png_height_map_is_scaled_and_placed) {
  const ScratchFolder dir("heightmap");
  const std::string path = (dir.path / "peak.png").string();
  // 201 x 101 pixels, 40 m apart: a peak of 3000 m (code 49152 of 65535 at a scale of 4000 m) at
  // column 150, row 20 (2000 m east, 1200 m north of the centre), a cone of 1 km radius.
  auto code = [](int x, int y) {
    const double d = std::hypot(x - 150.0, y - 20.0) * 40.0;
    return std::round(49152.0 * std::max(0.0, 1.0 - d / 1000.0));
  };
  write_gdal_image(path, "PNG", GDT_UInt16, 201, 101, code);
  const HeightGrid g = read_height_map(path, height_map(40.0, 4000.0, 30000.0, 40.0));
  // The grid reaches as far as the image: 100 and 50 pixels from its centre.
  BOOST_TEST(g.columns == 201);
  BOOST_TEST(g.rows == 101);
  BOOST_TEST(g.east0_m == -4000.0);
  BOOST_TEST(g.north0_m == -2000.0);
  // Samples on pixel centres are the pixels: grid row r is image row 100 - r.
  double worst = 0.0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c)
      worst = std::max(worst, std::abs(g.at(c, r) - code(c, 100 - r) / 65535.0 * 4000.0));
  BOOST_TEST(worst < 1e-3);
  const Terrain t(g, R);
  BOOST_TEST(std::abs(t.height_at(2000.0, 1200.0) - 49152.0 / 65535.0 * 4000.0) < 1e-3);
  BOOST_TEST(t.height_at(-2000.0, -1200.0) == 0.0);
  // Between pixel centres, bilinear: halfway between two samples of the cone's flank.
  const double between = t.height_at(2020.0, 1200.0);
  BOOST_TEST(std::abs(between - 0.5 * (code(150, 20) + code(151, 20)) / 65535.0 * 4000.0) < 1e-3);
  // A coarser grid over a part of it (extent 1000 m, spacing 100 m) samples the same surface.
  const HeightGrid coarse = read_height_map(path, height_map(40.0, 4000.0, 1000.0, 100.0));
  BOOST_TEST(coarse.columns == 21);
  BOOST_TEST(coarse.rows == 21);
}

// An OpenEXR height map: its values as stored, times the scale, plus the offset; negative heights
// raised to the sphere's.
BOOST_AUTO_TEST_CASE(exr_height_map_values_as_stored) {
  const ScratchFolder dir("heightmap");
  const std::string path = (dir.path / "ramp.exr").string();
  const int w = 65, h = 33;
  std::vector<float> y(static_cast<size_t>(w) * h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) y[static_cast<size_t>(r) * w + c] = static_cast<float>(10.0 * c - 5.0 * r);
  write_exr_channels(path, w, h, {{"Y", &y}}, {});
  HeightMapSampling s = height_map(25.0, 2.0, 30000.0, 25.0);
  s.height_offset_m = 100.0;
  const HeightGrid g = read_height_map(path, s);
  BOOST_TEST(g.columns == w);
  BOOST_TEST(g.rows == h);
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      const double want = std::max(0.0, 2.0 * (10.0 * c - 5.0 * (h - 1 - r)) + 100.0);
      BOOST_TEST(std::abs(g.at(c, r) - want) < 1e-3, "column " << c << ", row " << r);
    }
}

BOOST_AUTO_TEST_CASE(unusable_height_maps_are_refused_naming_the_file_or_the_key) {
  const ScratchFolder dir("heightmap");
  const HeightMapSampling s = height_map(30.0, 1.0, 10000.0, 30.0);
  std::vector<float> flat(16 * 16, 100.0f);
  // No channel to take.
  const std::string ab = (dir.path / "ab.exr").string();
  write_exr_channels(ab, 16, 16, {{"A", &flat}, {"B", &flat}}, {});
  std::string m = message_of([&] { read_height_map(ab, s); });
  BOOST_TEST(m.find("terrain.file") != std::string::npos, m);
  BOOST_TEST(m.find("ab.exr") != std::string::npos, m);
  BOOST_TEST(m.find("A, B") != std::string::npos, m);
  // A value that is not finite.
  std::vector<float> hole = flat;
  hole[8 * 16 + 8] = NAN;
  const std::string nan = (dir.path / "nan.exr").string();
  {  // (skyspec's own writer refuses it)
    Imf::Header header(16, 16);
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile out(nan.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(hole.data()), sizeof(float), 16 * sizeof(float)));
    out.setFrameBuffer(frame);
    out.writePixels(16);
  }
  m = message_of([&] { read_height_map(nan, s); });
  BOOST_TEST(m.find("finite") != std::string::npos, m);
  // Absurd once scaled: 100 x 100 m.
  const std::string tall = (dir.path / "tall.exr").string();
  write_exr_channels(tall, 16, 16, {{"Y", &flat}}, {});
  m = message_of([&] { read_height_map(tall, height_map(30.0, 100.0, 10000.0, 30.0)); });
  BOOST_TEST(m.find("9000") != std::string::npos, m);
  // Too small, not an image, no scale.
  const std::string one = (dir.path / "one.png").string();
  write_gdal_image(one, "PNG", GDT_Byte, 1, 1, [](int, int) { return 7.0; });
  m = message_of([&] { read_height_map(one, s); });
  BOOST_TEST(m.find("2 x 2") != std::string::npos, m);
  const std::string text = (dir.path / "notes.png").string();
  skyspec::test::write_text(dir.path / "notes.png", "not an image\n");
  m = message_of([&] { read_height_map(text, s); });
  BOOST_TEST(m.find("notes.png") != std::string::npos, m);
  m = message_of([&] { read_height_map(one, height_map(0.0, 1.0, 10000.0, 30.0)); });
  BOOST_TEST(m.find("terrain.heightmap.pixel_m") != std::string::npos, m);
  // A PNG's no-data value (GDAL's) is refused like a DEM's hole.
  const std::string nodata = (dir.path / "nodata.tif").string();
  write_gdal_image(nodata, "GTiff", GDT_Int16, 16, 16, [](int x, int) { return x == 8 ? -32768.0 : 50.0; });
  {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(nodata.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
    BOOST_REQUIRE(ds);
    ds->GetRasterBand(1)->SetNoDataValue(-32768.0);
  }
  m = message_of([&] { read_height_map(nodata, s); });
  BOOST_TEST(m.find("no-data") != std::string::npos, m);
}

// An albedo map read as a DEM is, at each grid sample's latitude and longitude, with the band's
// scale applied (0.001, as land-cover albedo products store it).
BOOST_AUTO_TEST_CASE(georeferenced_albedo_map_lands_on_the_grid) {
  const ScratchFolder dir("albedo");
  const std::string dem = (dir.path / "cone.tif").string(), map = (dir.path / "albedo.tif").string();
  write_geotiff(dem, 500, 500, kGeographic, 4326, [](double lon, double lat) { return cone(lat, lon); });
  write_geotiff(map, 500, 500, kGeographic, 4326, [](double lon, double) { return lon < 7.25 ? 200.0 : 800.0; });
  {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(map.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
    BOOST_REQUIRE(ds);
    ds->GetRasterBand(1)->SetScale(0.001);
  }
  const ElevationSampling s = around_reference(5000.0, 100.0);
  const HeightGrid g = read_elevation_raster(dem, s);
  const std::vector<float> a = read_georeferenced_albedo_map(map, g, s);
  BOOST_REQUIRE(a.size() == g.height_m.size());
  for (int r = 0; r < g.rows; r += 10)
    for (int c = 0; c < g.columns; ++c) {
      if (std::abs(g.east_m(c)) < 200.0) continue;  // the edge between the halves, interpolated
      const float want = g.east_m(c) < 0.0 ? 0.2f : 0.8f;
      BOOST_TEST(std::abs(a[static_cast<size_t>(r) * g.columns + c] - want) < 1e-6f, "column " << c << ", row " << r);
    }
  // Factors beyond [0, 1] are refused naming the key and the file.
  const std::string bright = (dir.path / "bright.tif").string();
  write_geotiff(bright, 500, 500, kGeographic, 4326, [](double, double) { return 1.5; });
  const std::string m = message_of([&] { read_georeferenced_albedo_map(bright, g, s); });
  BOOST_TEST(m.find("terrain.albedo_map") != std::string::npos, m);
  BOOST_TEST(m.find("bright.tif") != std::string::npos, m);
  BOOST_TEST(m.find("albedo factors between 0 and 1") != std::string::npos, m);
}

// An albedo image over a height map's ground: a 2 x 2 PNG (codes 51 and 204 of 255, west and east)
// spread over the 4040 m the 101 pixels of 40 m cover, its pixel centres 1010 m either side.
BOOST_AUTO_TEST_CASE(albedo_image_spreads_over_the_height_maps_ground) {
  const ScratchFolder dir("albedo");
  const std::string heights = (dir.path / "flat.png").string(), map = (dir.path / "albedo.png").string();
  write_gdal_image(heights, "PNG", GDT_UInt16, 101, 101, [](int, int) { return 1000.0; });
  write_gdal_image(map, "PNG", GDT_Byte, 2, 2, [](int x, int) { return x == 0 ? 51.0 : 204.0; });
  const HeightGrid g = read_height_map(heights, height_map(40.0, 100.0, 30000.0, 40.0));
  int width = 0, height = 0;
  height_map_pixels(heights, width, height);
  BOOST_TEST(width == 101);
  BOOST_TEST(height == 101);
  const std::vector<float> a = read_albedo_image(map, g, width * 40.0, height * 40.0);
  BOOST_REQUIRE(a.size() == g.height_m.size());
  const auto at = [&](double east_m) {
    const int c = static_cast<int>(std::lround((east_m - g.east0_m) / g.spacing_m));
    return a[static_cast<size_t>(50) * g.columns + c];
  };
  BOOST_TEST(std::abs(at(-2000.0) - 0.2f) < 1e-6f);
  BOOST_TEST(std::abs(at(-1040.0) - 0.2f) < 1e-6f);
  BOOST_TEST(std::abs(at(0.0) - 0.5f) < 1e-6f);
  BOOST_TEST(std::abs(at(520.0) - (0.5f + 0.3f * 520.0f / 1010.0f)) < 1e-5f);
  BOOST_TEST(std::abs(at(2000.0) - 0.8f) < 1e-6f);
}

BOOST_AUTO_TEST_SUITE_END()
