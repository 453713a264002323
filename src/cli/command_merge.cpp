// `skyspec merge`: tiles rendered with --pixel-bounds (on several machines, or by a job) assembled
// into the whole image's spectral EXR, streaming (io/exr_merge.hpp).

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "commands.hpp"
#include "io/exr_merge.hpp"
#include "progress.hpp"
#include "skyspec/error.hpp"

namespace skyspec::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> tiles;
  std::string out;
  bool quiet = false;
};

int run_merge(const MergeOptions& o) {
  if (o.out.empty()) throw InputError("--out", "(missing)", "the merged EXR's path");
  std::vector<std::filesystem::path> tiles(o.tiles.begin(), o.tiles.end());
  std::vector<NamedInput> inputs;
  for (const auto& t : tiles) inputs.push_back({"TILES", t});
  refuse_output_replacing_input(o.out, "--out", inputs);
  // Before the merge, not after it (a large panorama's merge took minutes before being refused): a
  // folder, a link or a device is not a file this command may replace.
  if (std::filesystem::is_directory(std::filesystem::symlink_status(o.out)))
    throw InputError("--out", "'" + o.out + "'", "the merged EXR's file name (this is a folder)");
  refuse_to_replace_non_regular(o.out);
  const auto parent = std::filesystem::absolute(o.out).parent_path();
  ensure_writable_directory(parent, "--out");
  ProgressBar bar("merging", o.quiet);
  const MergeSummary m = merge_spectral_exr_tiles(tiles, o.out, [&](int done, int total) { bar.update(done, total); });
  bar.finish();
  if (!o.quiet)
    std::cout << "merged " << m.tiles << " tile(s) into " << o.out << " (" << m.width << "x" << m.height << ", "
              << m.channels << " channels, " << m.band_rows << " rows in memory at a time)\n";
  return kExitOk;
}

}  // namespace

Command add_merge_command(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  auto* cmd = app.add_subcommand("merge", "Assemble tiles rendered with --pixel-bounds into the whole image's EXR");
  cmd->footer(
      "Example:\n"
      "  skyspec render --camera equirectangular --width 8192 --height 4096 --pixel-bounds 0,8192,0,2048 --out top\n"
      "  skyspec render --camera equirectangular --width 8192 --height 4096 --pixel-bounds 0,8192,2048,4096 --out "
      "bottom\n"
      "  skyspec merge top/sky.exr bottom/sky.exr --out pano.exr\n"
      "The tiles must be of one render (same scene, size and settings) and cover the image exactly once; the\n"
      "result is byte for byte the EXR of the whole render. Memory: a band of scanlines, not the image.");
  cmd->add_option("TILES", o->tiles, "the tile EXRs")->required();
  cmd->add_option("--out", o->out, "the merged spectral EXR")->required();
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  return {cmd, [o] { return run_merge(*o); },
          [o] {
            if (o->out.empty()) throw InputError("--out", "(missing)", "the merged EXR's path");
          }};
}

}  // namespace skyspec::cli
