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

// The pixels (one float plane per channel, `names`' order) written with OpenEXRCore on `threads`
// threads: each takes the next line block, compresses it, and whoever finds the next block of the
// file ready writes it and those after it that are ready too.
void write_with_core(const char* path, int w, int h, const std::vector<std::string>& names,
                     const std::vector<std::vector<float>>& pixels, exr_compression_t compression, int threads) {
  exr_context_t ctx = nullptr;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.zip_level = 4;  // the C++ library's default in OpenEXR 3.1 (the same files)
  check(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init), "exr_start_write");
  int part = 0;
  check(exr_add_part(ctx, "", EXR_STORAGE_SCANLINE, &part), "exr_add_part");
  check(exr_initialize_required_attr_simple(ctx, part, w, h, compression), "exr_initialize_required_attr_simple");
  for (const std::string& n : names)
    check(exr_add_channel(ctx, part, n.c_str(), EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
          "exr_add_channel");
  check(exr_write_header(ctx), "exr_write_header");
  int32_t rows = 1;
  check(exr_get_scanlines_per_chunk(ctx, part, &rows), "exr_get_scanlines_per_chunk");
  const int blocks = (h + rows - 1) / rows;
  std::mutex mutex;
  std::map<int, std::vector<unsigned char>> ready;
  int taken = 0, next = 0;
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
          if (taken == blocks || failure) break;
          b = taken++;
        }
        exr_chunk_info_t chunk{};
        check(exr_write_scanline_chunk_info(ctx, part, b * rows, &chunk), "exr_write_scanline_chunk_info");
        if (!initialised)
          check(exr_encoding_initialize(ctx, part, &chunk, &enc), "exr_encoding_initialize");
        else
          check(exr_encoding_update(ctx, part, &chunk, &enc), "exr_encoding_update");
        for (int c = 0; c < enc.channel_count; ++c) {
          size_t k = 0;
          while (names[k] != enc.channels[c].channel_name) ++k;
          enc.channels[c].encode_from_ptr = reinterpret_cast<const uint8_t*>(pixels[k].data() + size_t(b) * rows * w);
          enc.channels[c].user_pixel_stride = 4;
          enc.channels[c].user_line_stride = 4 * w;
          enc.channels[c].user_data_type = EXR_PIXEL_FLOAT;
          enc.channels[c].user_bytes_per_element = 4;
        }
        if (!initialised) check(exr_encoding_choose_default_routines(ctx, part, &enc), "choose routines");
        initialised = true;
        enc.yield_until_ready_fn = nullptr;
        enc.write_fn = nullptr;
        check(exr_encoding_run(ctx, part, &enc), "exr_encoding_run");
        const bool smaller = enc.compressed_bytes < enc.packed_bytes;
        const auto* bytes = static_cast<const unsigned char*>(smaller ? enc.compressed_buffer : enc.packed_buffer);
        std::vector<unsigned char> block(bytes, bytes + (smaller ? enc.compressed_bytes : enc.packed_bytes));
        std::unique_lock<std::mutex> lock(mutex);
        ready[b] = std::move(block);
        if (writing) continue;
        writing = true;
        while (!ready.empty() && ready.begin()->first == next) {
          std::vector<unsigned char> data = std::move(ready.begin()->second);
          ready.erase(ready.begin());
          lock.unlock();
          check(exr_write_scanline_chunk(ctx, part, next * rows, data.data(), data.size()), "exr_write_scanline_chunk");
          lock.lock();
          ++next;
        }
        writing = false;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      failure = std::current_exception();
    }
    if (initialised) exr_encoding_destroy(ctx, &enc);
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  if (next != blocks) throw std::runtime_error("blocks left unwritten");
  check(exr_finish(&ctx), "exr_finish");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: exr_codecs IN.exr [OUT_FOLDER] [REPEATS]\n");
    return 2;
  }
  try {
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
