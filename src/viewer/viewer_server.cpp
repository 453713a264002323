#include "viewer/viewer_server.hpp"

#include <httplib.h>

#include <cstdio>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "base/cancellation.hpp"
#include "base/embedded_data.hpp"
#include "skyspec/error.hpp"

namespace skyspec::viewer {
namespace {

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host == "[::1]" || host.rfind("127.", 0) == 0;
}

void send_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(body.dump(), "application/json");
}

// The query's (name, value) pairs (httplib keeps them sorted by name; a name given twice keeps
// both, and the last wins).
Query query_of(const httplib::Request& req) {
  Query q;
  for (const auto& [k, v] : req.params) q.emplace_back(k, v);
  return q;
}

}  // namespace

void check_host(const std::string& host, bool allow_remote) {
  if (host.empty()) throw InputError(viewer_setting::kHost, "\"\"", "an address to listen on, e.g. 127.0.0.1");
  if (!allow_remote && !is_loopback(host))
    throw InputError(viewer_setting::kHost, "\"" + host + "\"",
                     std::string("a loopback address (127.0.0.1, ::1 or localhost); add ") +
                         viewer_setting::kAllowRemote + " to serve other machines");
}

struct ViewerServer::Impl {
  ViewerBase base;
  ServerOptions options;
  httplib::Server server;
  std::mutex rendering;  // one render at a time: each uses every thread it may
  std::string state_json;
  // The scattering tables of an atmosphere not at hand are built on a thread of their own while
  // frames are previews (view_requests.hpp); one build at a time.
  std::mutex building;
  std::thread builder;
  bool builder_running = false;  // guarded by `building`
  std::string build_error;       // the last build's failure, reported by the next frame

  ~Impl() { join_builder(); }

  // Waits for a table build under way (outside the lock: the builder takes it to finish).
  void join_builder() {
    std::thread finishing;
    {
      std::lock_guard<std::mutex> lock(building);
      finishing = std::move(builder);
    }
    if (finishing.joinable()) finishing.join();
  }

  // Starts building the scene's tables unless a build is under way; throws a failed build's error.
  void start_build(const Scene& scene) {
    std::lock_guard<std::mutex> lock(building);
    if (builder_running) return;
    if (!build_error.empty()) {
      const std::string error = build_error;
      build_error.clear();  // the next frame tries again
      throw Error("building the scattering tables failed: " + error);
    }
    if (builder.joinable()) builder.join();
    builder_running = true;
    builder = std::thread([this, scene] {
      std::string error;
      try {
        build_scattering_tables(scene);
      } catch (const Cancelled&) {  // the server is stopping
      } catch (const std::exception& e) {
        error = e.what();
      }
      std::lock_guard<std::mutex> done(building);
      build_error = error;
      builder_running = false;
    });
  }

  // Runs `work` and maps the library's errors to HTTP: bad input 400, cancelled 503, others 500.
  template <typename Work>
  void answer(httplib::Response& res, Work&& work) {
    try {
      work();
    } catch (const InputError& e) {  // in the page's words: its query names
      const InputError page = e.respelled({{display_setting::kView, "view"}});
      send_json(res, 400, {{"error", page.what()}, {"setting", page.setting()}});
    } catch (const Cancelled&) {
      send_json(res, 503, {{"error", "skyspec view is stopping"}});
    } catch (const std::exception& e) {
      send_json(res, 500, {{"error", e.what()}});
    }
  }

  void routes() {
    server.Get("/", [](const httplib::Request&, httplib::Response& res) {
      const std::string_view page = embedded_file("viewer/index.html");
      res.set_header("Cache-Control", "no-store");
      res.set_content(std::string(page), "text/html; charset=utf-8");
    });
    server.Get("/favicon.ico", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
    server.Get("/api/state", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        std::string body = state_json;
        if (req.has_param("preset")) {  // a preset's values, for the page's controls
          ViewerBase preset = base;
          preset.scene_toml = scene_to_toml(SceneLoader(req.get_param_value("preset")).finish());
          body = viewer_state(preset).dump();
        }
        res.set_header("Cache-Control", "no-store");
        res.set_content(body, "application/json");
      });
    });
    server.Get("/api/frame", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        const ViewRequest request = parse_view_request(base, query_of(req));
        std::lock_guard<std::mutex> lock(rendering);
        const TablesAtHand tables = tables_at_hand(request.scene);
        if (tables != TablesAtHand::exact) start_build(request.scene);
        const Frame frame = render_frame(request, tables);
        char seconds[64];
        std::snprintf(seconds, sizeof seconds, "%.4f", frame.render_seconds);
        res.set_header("X-Skyspec-Render-Seconds", seconds);
        std::snprintf(seconds, sizeof seconds, "%.4f", frame.encode_seconds);
        res.set_header("X-Skyspec-Encode-Seconds", seconds);
        res.set_header("X-Skyspec-Exposure", frame.exposure);
        res.set_header("X-Skyspec-Preview", frame.preview);
        res.set_header("Cache-Control", "no-store");
        res.set_content(frame.png, "image/png");
      });
    });
    server.Get("/api/spectrum", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        const Query query = query_of(req);
        const ViewRequest request = parse_view_request(base, query);
        std::lock_guard<std::mutex> lock(rendering);
        const TablesAtHand tables = tables_at_hand(request.scene);
        if (tables != TablesAtHand::exact) start_build(request.scene);
        if (tables == TablesAtHand::none) {  // all orders need tables: ask again once the preview's are built
          res.set_header("Retry-After", "2");
          send_json(res, 503,
                    {{"error", "the scattering tables of this atmosphere are being built: click again in a moment"}});
          return;
        }
        send_json(res, 200, spectrum_at(request, query, tables));
      });
    });
    server.Post("/api/export", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        const ViewRequest request = parse_view_request(base, query_of(req));
        std::lock_guard<std::mutex> lock(rendering);
        send_json(res, 200, export_view(request, options.export_directory));
      });
    });
    server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
      if (res.status == 404 && res.body.empty()) send_json(res, 404, {{"error", "no such page: " + req.path}});
    });
    if (options.log_requests)
      server.set_logger([](const httplib::Request& req, const httplib::Response& res) {
        std::cerr << "skyspec view: " << req.method << ' ' << req.path << " -> " << res.status << '\n';
      });
  }
};

ViewerServer::ViewerServer(ViewerBase base, ServerOptions options) : impl_(std::make_unique<Impl>()) {
  check_host(options.host, options.allow_remote);
  if (options.port < 0 || options.port > 65535)
    throw InputError(viewer_setting::kPort, std::to_string(options.port),
                     "a port from 1 to 65535, or 0 for any free port");
  impl_->base = std::move(base);
  impl_->options = std::move(options);
  impl_->state_json = viewer_state(impl_->base).dump();  // the base scene and display checked now
  impl_->routes();
}

ViewerServer::~ViewerServer() = default;

int ViewerServer::bind() {
  const ServerOptions& o = impl_->options;
  const std::string host = o.host == "[::1]" ? "::1" : o.host;
  int port = o.port;
  if (o.port == 0)
    port = impl_->server.bind_to_any_port(host);
  else if (!impl_->server.bind_to_port(host, o.port))
    port = -1;
  if (port <= 0)
    throw IoError("cannot listen on " + o.host + ":" + std::to_string(o.port) +
                  " (in use, or not an address of this machine); --port 0 picks a free port");
  return port;
}

void ViewerServer::serve() { impl_->server.listen_after_bind(); }

void ViewerServer::stop() {
  impl_->server.stop();
  impl_->join_builder();  // a table build under way ends first (at once when cancelled)
}

}  // namespace skyspec::viewer
