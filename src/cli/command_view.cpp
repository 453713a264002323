// `skyspec view`: the interactive viewer, a local web server over the library (src/viewer/).

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "base/memory_reuse.hpp"
#include "commands.hpp"
#include "display_options.hpp"
#include "scene_options.hpp"
#include "skyspec/cancellation.hpp"
#include "skyspec/error.hpp"
#include "viewer/viewer_server.hpp"

namespace skyspec::cli {
namespace {

std::vector<KeyFlag> view_flags() {
  std::vector<KeyFlag> flags = camera_flags(true);
  append_flags(flags, sun_flags());
  append_flags(flags, spectrum_flags());
  return flags;
}

struct ViewOptions {
  SceneOptions scene{"default", {}, {}, view_flags()};
  DisplayOptions display;
  viewer::ServerOptions server;
  std::string out = "skyspec-view";
  int threads = 0;
  bool quiet = false;
};

viewer::ViewerBase base_of(const ViewOptions& o) {
  viewer::ViewerBase base;
  base.scene_toml = scene_to_toml(load_scene(o.scene));
  base.display = display_settings(o.display);
  base.threads = o.threads;
  return base;
}

int run(ViewOptions& o) {
  // Frame after frame the same large blocks: kept rather than faulted in again (memory_reuse.hpp).
  keep_freed_memory_for_reuse();
  if (o.threads < 0) throw InputError("--threads", std::to_string(o.threads), "0 (all cores) or more");
  // The folder is made by the first export; what stands in its way is refused now, not then.
  std::error_code ec;
  const auto kind = std::filesystem::symlink_status(o.out, ec).type();
  if (kind != std::filesystem::file_type::not_found && kind != std::filesystem::file_type::directory)
    throw InputError("--out", "\"" + o.out + "\"", "a folder for the exports (this is not one)");
  o.server.export_directory = o.out;
  viewer::ViewerServer server(base_of(o), o.server);
  const int port = server.bind();
  const std::string host = o.server.host.find(':') != std::string::npos && o.server.host.front() != '['
                               ? "[" + o.server.host + "]"
                               : o.server.host;
  // The address on its own line, flushed at once: scripts and tests read it.
  std::cout << "skyspec view: serving http://" << host << ":" << port << "/ (exports go to " << o.out
            << "; Ctrl-C stops)" << std::endl;
  std::thread serving([&server] { server.serve(); });
  while (!cancellation_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  server.stop();
  serving.join();
  if (!o.quiet) std::cout << "skyspec view: stopped" << std::endl;
  return kExitOk;
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewOptions>();
  auto* cmd = app.add_subcommand("view", "Watch the sky in a web browser while you move the sun and change the air");
  cmd->footer(
      "Example:\n"
      "  skyspec view --preset hazy        then open the address it prints\n"
      "The page renders with the same engine as `skyspec render` (the scene's grid and orders; the page picks the\n"
      "size). Export writes view-NNNN.exr, .png and .toml into --out: `skyspec render --scene view-NNNN.toml`\n"
      "renders the same files. Serves on 127.0.0.1 unless --host and --allow-remote say otherwise.");
  add_scene_options(*cmd, o->scene);
  add_quality_option(*cmd, o->scene);
  add_display_options(*cmd, o->display, {false, false});
  cmd->add_option("--host", o->server.host, "address to listen on (default 127.0.0.1; others need --allow-remote)");
  cmd->add_option("--port", o->server.port, "port (default 8421; 0: any free port, printed)");
  cmd->add_flag("--allow-remote", o->server.allow_remote,
                "listen on a non-loopback --host: anyone who reaches it can render and export");
  cmd->add_option("--out", o->out, "folder of exported files (default skyspec-view, created on the first export)");
  cmd->add_option("--threads", o->threads, "render threads (0: all cores)");
  cmd->add_flag("--log", o->server.log_requests, "print each request on standard error");
  cmd->add_flag("-q,--quiet", o->quiet, "no message when stopping");
  return {cmd, [o] { return run(*o); },
          [o] {  // run's checks before serving (Command::validate)
            viewer::check_host(o->server.host, o->server.allow_remote);
            viewer::viewer_state(base_of(*o));
          }};
}

}  // namespace skyspec::cli
