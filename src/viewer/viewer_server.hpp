// `skyspec view`'s web server: the page and its API over HTTP (cpp-httplib), on a loopback address
// unless the user allows others. Every request is answered from the library through
// view_requests.hpp; one render runs at a time (each uses all of render.threads).
//
//   GET  /                 the page (embedded: no external resources, works offline)
//   GET  /api/state        the base scene's values, presets, cameras, views (view_requests.hpp)
//   GET  /api/frame?...    a frame, image/png; X-Skyspec-Render-Seconds, X-Skyspec-Encode-Seconds,
//                          X-Skyspec-Exposure, X-Skyspec-Preview (a new atmosphere's tables are
//                          built on a thread of their own meanwhile)
//   GET  /api/spectrum?... the spectrum under pixel (x, y), JSON (503 while its tables are built)
//   POST /api/export?...   full-quality files of the query's scene, JSON
// A bad query gets 400 with {"error", "setting"}; a failed write 500 with {"error"}.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "viewer/view_requests.hpp"

namespace skyspec::viewer {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8421;  ///< 0: any free port
  /// Serve on an address other than a loopback one (127.0.0.0/8, ::1, localhost). Anyone who can
  /// reach it can then render and export into the export folder.
  bool allow_remote = false;
  std::filesystem::path export_directory;
  bool log_requests = false;
};

/// Throws InputError naming "--host" unless host is a loopback address or allow_remote is set.
void check_host(const std::string& host, bool allow_remote);

class ViewerServer {
 public:
  ViewerServer(ViewerBase base, ServerOptions options);
  ~ViewerServer();
  /// Binds the address; returns the port (the chosen one for port 0). IoError when it cannot.
  int bind();
  /// Serves until stop() (from another thread); returns then.
  void serve();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace skyspec::viewer
