// How fast OpenEXR's lossless codecs write a spectral EXR, and how small (bench/run_benchmarks.sh).
//
// Reads an EXR (all channels as 32-bit floats, as skyspec writes them), then writes the same pixels
// to a file in memory-backed /dev/shm (or the folder given) with each lossless codec the library
// offers, on 1 and 2 threads, keeping each codec's fastest of `repeats` writes, twice: with the C++
// library's OutputFile (its own thread pool), and with the C core library (OpenEXRCore), each thread
// compressing the next line block and whichever holds the next one in the file's order writing
// what is ready (as skyspec's writer does, without the image's rows). Prints one tab-separated line
// per codec, library and thread count:
//
//   codec  threads  seconds  raw_bytes  file_bytes
//
// codec is "piz" (C++ library) or "piz-core"; raw_bytes is the pixels' size as floats (what the
// codec is given); file_bytes the written file. Built by run_benchmarks.sh with g++ -O2 and
// pkg-config's OpenEXR flags.
//
//   exr_codecs IN.exr [OUT_FOLDER] [REPEATS]
//
// With --same, the codec alone on a render's own pixels (issue 37's target 6): IN is read back 1024
// rows at a time and each band written with PIZ by both libraries on THREADS threads, into files in
// OUT_FOLDER (the render's own folder, so that both write to the same disk), timing the writing
// only (each file's opening, its bands and its completion); prints the lines "piz" and "piz-core".
// Memory: the band (1024 rows of IN's channels as floats: 2.8 GB for case 5) and the libraries' buffers;
// between bands the threads wait for the slowest block (one of 32 per band and thread).
//
//   exr_codecs --same IN.exr OUT_FOLDER THREADS
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/openexr.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

void check(exr_result_t result, const char* what) {
  if (result != EXR_ERR_SUCCESS)
    throw std::runtime_error(std::string(what) + ": " + exr_get_default_error_message(result));
}

// A file written with OpenEXRCore band by band: write_band() compresses a band's line blocks on
// `threads` threads, each taking the next block, and whoever finds the next block of the file ready
// writes it and those after it that are ready too (as skyspec's writer does).
class CoreWriter {
 public:
  CoreWriter(const char* path, int w, int h, const std::vector<std::string>& names, exr_compression_t compression)
      : w_(w), h_(h), names_(names) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.zip_level = 4;  // the C++ library's default in OpenEXR 3.1 (the same files)
    check(exr_start_write(&ctx_, path, EXR_WRITE_FILE_DIRECTLY, &init), "exr_start_write");
    check(exr_add_part(ctx_, "", EXR_STORAGE_SCANLINE, &part_), "exr_add_part");
    check(exr_initialize_required_attr_simple(ctx_, part_, w, h, compression), "exr_initialize_required_attr_simple");
    for (const std::string& n : names)
      check(exr_add_channel(ctx_, part_, n.c_str(), EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
            "exr_add_channel");
    check(exr_write_header(ctx_), "exr_write_header");
    check(exr_get_scanlines_per_chunk(ctx_, part_, &rows_), "exr_get_scanlines_per_chunk");
  }
  CoreWriter(const CoreWriter&) = delete;
  CoreWriter& operator=(const CoreWriter&) = delete;
  ~CoreWriter() {
    if (ctx_) exr_finish(&ctx_);
  }
  int rows_per_block() const { return rows_; }
  // Rows first_row .. first_row + count - 1 (first_row a multiple of rows_per_block(); count one
  // too, or reaching the last row), from planes of `count` rows in names' order.
  void write_band(const std::vector<std::vector<float>>& band, int first_row, int count, int threads) {
    const int b_begin = first_row / rows_, b_end = (first_row + count + rows_ - 1) / rows_;
    std::mutex mutex;
    std::map<int, std::vector<unsigned char>> ready;
    int taken = b_begin;
    bool writing = false;
    std::exception_ptr failure;
    const auto work = [&] {
      exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
      bool initialised = false;
      try {
        for (;;) {
          int b;
          {
            std::lock_guard<std::mutex> lock(mutex);
            if (taken == b_end || failure) break;
            b = taken++;
          }
          exr_chunk_info_t chunk{};
          check(exr_write_scanline_chunk_info(ctx_, part_, b * rows_, &chunk), "exr_write_scanline_chunk_info");
          if (!initialised)
            check(exr_encoding_initialize(ctx_, part_, &chunk, &enc), "exr_encoding_initialize");
          else
            check(exr_encoding_update(ctx_, part_, &chunk, &enc), "exr_encoding_update");
          for (int c = 0; c < enc.channel_count; ++c) {
            size_t k = 0;
            while (names_[k] != enc.channels[c].channel_name) ++k;
            enc.channels[c].encode_from_ptr =
                reinterpret_cast<const uint8_t*>(band[k].data() + size_t(b * rows_ - first_row) * w_);
            enc.channels[c].user_pixel_stride = 4;
            enc.channels[c].user_line_stride = 4 * w_;
            enc.channels[c].user_data_type = EXR_PIXEL_FLOAT;
            enc.channels[c].user_bytes_per_element = 4;
          }
          if (!initialised) check(exr_encoding_choose_default_routines(ctx_, part_, &enc), "choose routines");
          initialised = true;
          enc.yield_until_ready_fn = nullptr;
          enc.write_fn = nullptr;
          check(exr_encoding_run(ctx_, part_, &enc), "exr_encoding_run");
          const bool smaller = enc.compressed_bytes < enc.packed_bytes;
          const auto* bytes = static_cast<const unsigned char*>(smaller ? enc.compressed_buffer : enc.packed_buffer);
          std::vector<unsigned char> block(bytes, bytes + (smaller ? enc.compressed_bytes : enc.packed_bytes));
          std::unique_lock<std::mutex> lock(mutex);
          ready[b] = std::move(block);
          if (writing) continue;
          writing = true;
          while (!ready.empty() && ready.begin()->first == next_) {
            std::vector<unsigned char> data = std::move(ready.begin()->second);
            ready.erase(ready.begin());
            lock.unlock();
            check(exr_write_scanline_chunk(ctx_, part_, next_ * rows_, data.data(), data.size()),
                  "exr_write_scanline_chunk");
            lock.lock();
            ++next_;
          }
          writing = false;
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        failure = std::current_exception();
      }
      if (initialised) exr_encoding_destroy(ctx_, &enc);
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    if (next_ != b_end) throw std::runtime_error("blocks left unwritten");
  }
  void finish() {
    if (next_ * rows_ < h_) throw std::runtime_error("rows left unwritten");
    exr_context_t ctx = ctx_;
    ctx_ = nullptr;
    check(exr_finish(&ctx), "exr_finish");
  }

 private:
  exr_context_t ctx_ = nullptr;
  int part_ = 0;
  int32_t rows_ = 1;
  int w_, h_;
  std::vector<std::string> names_;
  int next_ = 0;  // the next block of the file to write
};

// The pixels (one float plane per channel, `names`' order) written with OpenEXRCore on `threads` threads.
void write_with_core(const char* path, int w, int h, const std::vector<std::string>& names,
                     const std::vector<std::vector<float>>& pixels, exr_compression_t compression, int threads) {
  CoreWriter writer(path, w, h, names, compression);
  writer.write_band(pixels, 0, h, threads);
  writer.finish();
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// --same: IN's own pixels read back band by band (not timed) and written with PIZ on `threads`
// threads by both libraries, each into its own file in `folder`; only the writing is timed. Prints
// the two lines "piz" and "piz-core" of the table above.
int write_same_pixels(const char* in_path, const std::filesystem::path& folder, int threads) {
  Imf::setGlobalThreadCount(threads);
  Imf::InputFile in(in_path);
  const Imath::Box2i dw = in.header().dataWindow();
  const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  std::vector<std::string> names;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
    names.emplace_back(it.name());
  const std::filesystem::path cpp_path = folder / "exr_codecs.same.tmp.exr",
                              core_path = folder / "exr_codecs.same-core.tmp.exr";
  Imf::Header header(in.header().displayWindow(), dw);
  header.compression() = Imf::PIZ_COMPRESSION;
  for (const std::string& n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
  double cpp_seconds = 0.0, core_seconds = 0.0;
  {
    auto t0 = std::chrono::steady_clock::now();
    auto cpp_out = std::make_unique<Imf::OutputFile>(cpp_path.c_str(), header, threads);
    cpp_seconds += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    CoreWriter core_out(core_path.c_str(), w, h, names, EXR_COMPRESSION_PIZ);
    core_seconds += seconds_since(t0);
    const int band_rows = 32 * core_out.rows_per_block();  // 1024 rows for PIZ
    std::vector<std::vector<float>> band(names.size(), std::vector<float>(static_cast<size_t>(w) * band_rows));
    for (int y = 0; y < h; y += band_rows) {
      const int count = std::min(band_rows, h - y);
      Imf::FrameBuffer fb;
      for (size_t c = 0; c < names.size(); ++c)
        fb.insert(names[c], Imf::Slice(Imf::FLOAT,
                                       reinterpret_cast<char*>(band[c].data()) -
                                           (dw.min.x + (dw.min.y + static_cast<size_t>(y)) * w) * sizeof(float),
                                       sizeof(float), sizeof(float) * static_cast<size_t>(w)));
      in.setFrameBuffer(fb);
      in.readPixels(dw.min.y + y, dw.min.y + y + count - 1);
      t0 = std::chrono::steady_clock::now();
      cpp_out->setFrameBuffer(fb);
      cpp_out->writePixels(count);
      cpp_seconds += seconds_since(t0);
      t0 = std::chrono::steady_clock::now();
      core_out.write_band(band, y, count, threads);
      core_seconds += seconds_since(t0);
    }
    t0 = std::chrono::steady_clock::now();
    core_out.finish();
    core_seconds += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    cpp_out.reset();  // writes the offsets and closes the file
    cpp_seconds += seconds_since(t0);
  }
  const double raw = static_cast<double>(w) * h * static_cast<double>(names.size()) * sizeof(float);
  std::printf("piz\t%d\t%.4f\t%.0f\t%ju\n", threads, cpp_seconds, raw, std::filesystem::file_size(cpp_path));
  std::printf("piz-core\t%d\t%.4f\t%.0f\t%ju\n", threads, core_seconds, raw, std::filesystem::file_size(core_path));
  std::filesystem::remove(cpp_path);
  std::filesystem::remove(core_path);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || (std::string(argv[1]) == "--same" && argc != 5)) {
    std::fprintf(
        stderr,
        "usage: exr_codecs IN.exr [OUT_FOLDER] [REPEATS]\n       exr_codecs --same IN.exr OUT_FOLDER THREADS\n");
    return 2;
  }
  try {
    if (std::string(argv[1]) == "--same") return write_same_pixels(argv[2], argv[3], std::max(1, std::atoi(argv[4])));
    const std::filesystem::path folder = argc > 2 ? argv[2] : "/dev/shm";
    const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 2;
    const std::filesystem::path out_path = folder / "exr_codecs.tmp.exr";

    Imf::InputFile in(argv[1]);
    const Imath::Box2i dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    std::vector<std::string> names;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
      names.emplace_back(it.name());
    std::vector<std::vector<float>> pixels(names.size(), std::vector<float>(static_cast<size_t>(w) * h));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c)
      fb.insert(names[c], Imf::Slice(Imf::FLOAT,
                                     reinterpret_cast<char*>(pixels[c].data()) -
                                         (dw.min.x + dw.min.y * static_cast<size_t>(w)) * sizeof(float),
                                     sizeof(float), sizeof(float) * static_cast<size_t>(w)));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    const double raw = static_cast<double>(w) * h * static_cast<double>(names.size()) * sizeof(float);

    struct Codec {
      const char* name;
      Imf::Compression compression;
    };
    const Codec codecs[] = {{"none", Imf::NO_COMPRESSION},
                            {"rle", Imf::RLE_COMPRESSION},
                            {"zips", Imf::ZIPS_COMPRESSION},
                            {"zip", Imf::ZIP_COMPRESSION},
                            {"piz", Imf::PIZ_COMPRESSION}};
    const auto core_compression = [](Imf::Compression c) {
      return c == Imf::NO_COMPRESSION     ? EXR_COMPRESSION_NONE
             : c == Imf::RLE_COMPRESSION  ? EXR_COMPRESSION_RLE
             : c == Imf::ZIPS_COMPRESSION ? EXR_COMPRESSION_ZIPS
             : c == Imf::ZIP_COMPRESSION  ? EXR_COMPRESSION_ZIP
                                          : EXR_COMPRESSION_PIZ;
    };
    for (const int threads : {1, 2}) {
      Imf::setGlobalThreadCount(threads);
      for (const Codec& codec : codecs) {
        double best = 1e30;
        std::uintmax_t size = 0;
        for (int r = 0; r < repeats; ++r) {
          Imf::Header header(in.header().displayWindow(), dw);
          header.compression() = codec.compression;
          for (const std::string& n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
          const auto t0 = std::chrono::steady_clock::now();
          {
            Imf::OutputFile out(out_path.c_str(), header, threads);
            out.setFrameBuffer(fb);
            out.writePixels(h);
          }
          best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          size = std::filesystem::file_size(out_path);
        }
        std::printf("%s\t%d\t%.4f\t%.0f\t%ju\n", codec.name, threads, best, raw, size);
        std::fflush(stdout);
        best = 1e30;
        for (int r = 0; r < repeats; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          write_with_core(out_path.c_str(), w, h, names, pixels, core_compression(codec.compression), threads);
          best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          size = std::filesystem::file_size(out_path);
        }
        std::printf("%s-core\t%d\t%.4f\t%.0f\t%ju\n", codec.name, threads, best, raw, size);
        std::fflush(stdout);
      }
    }
    std::filesystem::remove(out_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_codecs: %s\n", e.what());
    return 1;
  }
  return 0;
}
