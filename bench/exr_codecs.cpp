// How fast OpenEXR's lossless codecs write a spectral EXR, and how small (bench/run_benchmarks.sh).
//
// Reads an EXR (all channels as 32-bit floats, as skyspec writes them), then writes the same pixels
// to a file in memory-backed /dev/shm (or the folder given) with each lossless codec the library
// offers, on 1 and 2 threads, keeping each codec's fastest of `repeats` writes. Prints one
// tab-separated line per codec and thread count:
//
//   codec  threads  seconds  raw_bytes  file_bytes
//
// raw_bytes is the pixels' size as floats (what the codec is given); file_bytes the written file.
// Built by run_benchmarks.sh with g++ -O2 and pkg-config's OpenEXR flags.
//
//   exr_codecs IN.exr [OUT_FOLDER] [REPEATS]
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

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
      }
    }
    std::filesystem::remove(out_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_codecs: %s\n", e.what());
    return 1;
  }
  return 0;
}
