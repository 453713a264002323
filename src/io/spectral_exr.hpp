// Spectral OpenEXR files in the layout of Fichet, Pacanowski & Wilkie 2021, "An OpenEXR Layout for
// Spectral Images" (JCGT 10(3)): one float channel per wavelength named "S0.<value>nm" with a
// decimal comma (e.g. "S0.550,000000nm"), header attributes spectralLayoutVersion = "1.0" and
// emissiveUnits = "W.m^-2.sr^-1", optional float EV, plus R, G, B linear Rec.709 preview channels
// and the chromaticities attribute for them.
//
// The writer streams: rows are handed over top to bottom in bands, so memory is bounded by one
// band, not the image. A band of whole line blocks can also be compressed on any thread
// (encode_rows), several at once, and written in order afterwards (write_encoded): a renderer
// compresses each band where it rendered it. The file is written under a temporary name and
// renamed on finish().
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace skyspec {

/// "S0.550,000000nm" for 550 (six decimals, comma as the decimal separator); "S1.550,000000nm"
/// for Stokes component 1, and so on to 3.
std::string spectral_channel_name(double lambda_nm, int stokes_component = 0);
/// The wavelength in nm of an emissive (S0) channel name in any unit the layout allows
/// ("S0.550,5nm", "S0.0,55um", "S0.550nm"); nothing if the name is not an S0 spectral channel.
std::optional<double> parse_spectral_channel_name(const std::string& name);
/// The Stokes component (0 to 3) and wavelength in nm of any emissive channel name ("S2.550,5nm").
std::optional<std::pair<int, double>> parse_stokes_channel_name(const std::string& name);

struct SpectralExrMetadata {
  std::map<std::string, std::string> strings;            ///< extra string attributes, e.g. "skyspec:scene"
  std::map<std::string, double> doubles;                 ///< extra double attributes, e.g. "skyspec:exposureScale"
  std::map<std::string, std::array<double, 3>> vectors;  ///< extra v3d attributes, e.g. "skyspec:sunRGB"
  std::optional<float> ev;                               ///< the layout's optional EV attribute
  /// OpenEXR's standard envmap attribute = latlong (ImfEnvmap.h): the image is a whole-sphere
  /// latitude-longitude panorama.
  bool latlong_envmap = false;
  /// S0 channels as 16-bit half floats (R, G, B stay float): a value above half's largest, 65504,
  /// is refused with IoError rather than written as infinity.
  bool half_spectral = false;
  /// A polarised image: S1, S2 and S3 channels at every wavelength beside S0 (each pixel's values
  /// come as S0 at all wavelengths, then S1, S2, S3), and the layout's polarisationHandedness =
  /// "right": each pixel's Stokes frame (e1, e2) has e1 x e2 = the light's direction of travel.
  bool polarised = false;
  std::string compression = "piz";  ///< lossless: piz, zip, zips, rle or none
  /// A tile of the image: only pixels [x0, x1) x [y0, y1) of the width x height image are stored
  /// (the file's dataWindow; its displayWindow stays the whole image). write_rows then takes rows
  /// of x1 - x0 pixels, y1 - y0 of them. Tiles are assembled by merge_spectral_exr_tiles.
  std::optional<std::array<int, 4>> data_window;
  /// Not stored in the file: how many cores write_rows may compress on (0: all; 1: the calling
  /// thread only, as for a render limited to one thread). encode_rows uses the caller's threads.
  int threads = 0;
};

/// The rows a spectral EXR's codec compresses together (its line block): 32 for "piz", 16 for
/// "zip", 1 for "zips", "rle" and "none" (OpenEXR's). SpectralExrWriter::rows_per_block() of a file
/// with that compression.
int spectral_exr_block_rows(const std::string& compression);

class SpectralExrWriter {
 public:
  /// Opens a temporary file beside final_path. rgb channels R, G, B are always written.
  SpectralExrWriter(const std::filesystem::path& final_path, int width, int height,
                    const std::vector<double>& wavelengths_nm, const SpectralExrMetadata& meta);
  ~SpectralExrWriter();  ///< removes the temporary file if finish() was not reached
  SpectralExrWriter(const SpectralExrWriter&) = delete;
  SpectralExrWriter& operator=(const SpectralExrWriter&) = delete;

  /// Write the next `rows` rows (continuing from the last row written), each of the data window's
  /// width (the image's, unless meta.data_window says otherwise).
  /// spectral: rows * width * n_wavelengths floats, pixel-major ([row][x][lambda]; polarised:
  /// rows * width * 4 * n_wavelengths, [row][x][S0..S3][lambda]);
  /// rgb: rows * width * 3 floats ([row][x][c]). Non-finite values are rejected with IoError.
  void write_rows(int rows, const float* spectral, const float* rgb);
  /// All rows written: close, fsync, rename. Throws IoError if rows are missing.
  void finish();

  /// Rows that the file's codec compresses together (its line block: 32 for PIZ, 16 for ZIP, 1
  /// for ZIPS, RLE and none).
  int rows_per_block() const;
  /// Rows compressed into the file's bytes, one byte string per line block, waiting to be written.
  struct EncodedRows {
    int first_row = 0, rows = 0;  ///< of the data window
    std::vector<std::vector<unsigned char>> blocks;
  };
  /// Checks and compresses `rows` rows starting at `first_row` (laid out as write_rows takes
  /// them): the band starts on a line block and ends on one or at the image's last row. Safe to
  /// call from several threads at once, for different bands; a band of several blocks is compressed
  /// in parallel in the caller's TBB arena unless meta.threads = 1. Throws IoError as write_rows.
  EncodedRows encode_rows(int first_row, int rows, const float* spectral, const float* rgb) const;
  /// Writes encoded rows: they must be the next rows of the file (IoError otherwise), and not
  /// mixed with rows that write_rows holds back because they did not yet fill a line block. Their
  /// byte strings are kept for the next encode_rows once written.
  void write_encoded(EncodedRows&& rows);

  /// A writer whose bytes go nowhere (the render-time estimate: what encoding costs).
  struct Discarding {};
  SpectralExrWriter(Discarding, int width, int height, const std::vector<double>& wavelengths_nm,
                    const SpectralExrMetadata& meta);
  /// The file's length so far (the whole file's after finish()).
  std::uint64_t bytes_written() const;

  struct Impl;     ///< opaque: the open file
  struct Encoder;  ///< opaque: one thread's line-block encoder

 private:
  void open(const std::filesystem::path& final_path, bool discard, int width, int height,
            const std::vector<double>& wavelengths_nm, const SpectralExrMetadata& meta);
  std::unique_ptr<Impl> impl_;
};

/// A spectral EXR read back into memory (tests, `convert` and other tools).
struct SpectralImage {
  int width = 0, height = 0;
  std::vector<double> wavelengths_nm;  ///< ascending
  std::vector<float> spectral;         ///< [y][x][lambda]
  std::vector<float> rgb;              ///< [y][x][c], empty if the file has no R, G, B
  std::vector<float> stokes;           ///< [y][x][S1..S3][lambda] of a polarised file, else empty
  std::map<std::string, std::string> string_attributes;
  std::optional<float> ev;
};
/// Throws IoError naming the file when it cannot be read or has no S0 channels.
SpectralImage read_spectral_exr(const std::filesystem::path& path);

}  // namespace skyspec
