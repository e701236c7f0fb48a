#pragma once
// The studio's HTTP server (issue 18): the paper's ViSim as a web page served by the binary.
// HTTP and JSON only, over the existing libraries; the page itself lives in studio/web/.
//
// Routes (docs/studio.md has request and response examples):
//   GET  /                           the web root's index.html
//   GET  /<path>                     a file below the web root (static assets)
//   GET  /api/health                 {"status": "ok", "version", "layout", "jobs", "uptime_s"}
//   GET  /api/layout                 the layout's summary (what `layout show` prints)
//   GET  /api/files                  {"roots": [names of the data roots]}
//   GET  /api/files/<root>/<path>    a file below a named data root, read-only
//   POST /api/trajectory/preview     a random trajectory's poses (studio/trajectory_api.h)
//   POST /api/jobs/trajectory        the same as a background job: 202 {"id", ...}
//   GET  /api/jobs                   every stored job, without results
//   GET  /api/jobs/<id>              a job's state, progress, message and result
//   GET  /api/jobs/<id>/events       the same as server-sent events until it has finished
//   DELETE /api/jobs/<id>            cancel: 200 (was pending), 202 (running: stops at its next
//                                    safe point), 409 (finished), 404
//   GET  /api/layout/plan?level=N    the floor plan raster of floor level N (default 0;
//                                    studio/floor_plan.h)
//   GET  /api/layout.glb             the layout as binary glTF (studio/layout_glb.h)
//   POST /api/design/path            keyframes -> the camera path and its warnings
//   POST /api/design/export          keyframes -> a trajectory file (studio/design_api.h)
//   POST /api/design/imu             keyframes -> the IMU samples along the path
//   POST /api/jobs/sequence          render the path as a sequence (studio/sequence_api.h)
//   POST /api/preview/frame          one frame's pass or low-spp colour as PNG
//                                    (studio/frame_preview.h)
// Errors are JSON {"error": one line, "file", "field"} with 400 (bad input: the command line's
// one-line messages), 401 (no or a wrong access token), 403 (a refused path or Host), 404, 405
// (with Allow), 409 (cancelling a finished job), 411 (chunked bodies), 413 (body over
// max_body_bytes), 415 (POST without application/json), 503 (job store full), 500 (a bug).
//
// Security rules: HTTPS when given a certificate and key (tls_cert, tls_key). With a token (the
// command line makes one unless told not to), every request carries it: `Authorization: Bearer
// TOKEN`, or the cookie inet_studio_token (HttpOnly, SameSite=Strict) set when a request brings
// ?token=TOKEN (a page request is then redirected to the same path without it); compared in
// constant time. Loopback by default (binding elsewhere needs allow_remote and warns); without
// allow_remote only Host headers naming the loopback are answered (DNS rebinding); files only
// below the web root and the data roots (studio/safe_path.h); POST bodies must be JSON (so a
// cross-site form cannot post, and a cross-site fetch needs a CORS preflight, which is refused);
// request bodies are limited; at most `threads` connections are served at once, previews are
// computed `compute_slots` at a time, jobs `job_workers` at a time with `max_jobs` stored.
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "studio/studio_layout.h"

namespace inet::studio {

struct StudioOptions {
  std::string host = "127.0.0.1";
  int port = 8080;                 ///< 0 = any free port (port() tells which)
  bool allow_remote = false;       ///< needed to bind an address other machines can reach
  std::filesystem::path web_root;  ///< static assets; empty = defaultWebRoot()
  /// Named folders whose files GET /api/files/<name>/... serves read-only. Names: letters,
  /// digits, '-', '_'.
  std::map<std::string, std::filesystem::path> data_roots;
  size_t max_body_bytes = size_t{1} << 20;
  int threads = 32;       ///< HTTP worker threads (connections served at once)
  int compute_slots = 0;  ///< previews computed at once; 0 = the machine's hardware threads
  int job_workers = 1;    ///< background jobs running at once
  int max_jobs = 64;      ///< background jobs stored
  int max_preview_frames = 5000;
  int max_job_frames = 100000;
  bool log_requests = false;  ///< one line per request on stderr
  /// The access token every request must carry ("" = none): a cookie the page gets from the
  /// printed URL's ?token=..., or `Authorization: Bearer TOKEN`. Letters, digits, '-', '_';
  /// 16..128 characters.
  std::string token;
  /// Where sequence jobs write (<out>/<layout name>/<sequence>/, as `generate --out`).
  std::filesystem::path out_dir = "out";
  /// Also serve out_dir read-only as the data root "out" (made if missing), so the page can
  /// show what the jobs wrote (the command line does; a "--data out=..." of its own wins).
  bool serve_out = false;
  /// HTTPS: a PEM certificate (chain) and its unencrypted PEM private key, both or neither
  /// (Debian's cpp-httplib is built with OpenSSL). The token cookie is then Secure.
  std::filesystem::path tls_cert, tls_key;
};

/// The studio's page: $INET_STUDIO_WEB, else the bundle the build made (<build>/studio/web),
/// else <prefix>/share/interiornet/studio/web next to the installed binary, else the source
/// tree's studio/web/unbuilt (a page saying how to build the page).
std::filesystem::path defaultWebRoot();

class StudioServer {
 public:
  /// Checks the options and binds the socket. InputError naming the option: a host that is not
  /// loopback without allow_remote, a port that cannot be bound, a missing web root or data
  /// root, a bad root name, limits out of range. With allow_remote and a non-loopback host,
  /// prints a warning on stderr.
  StudioServer(StudioOptions opt, std::shared_ptr<const StudioLayout> layout);
  ~StudioServer();  ///< stop()
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  /// The port bound (the chosen one when the options said 0).
  int port() const;
  /// The address the socket is bound to, as the kernel reports it ("127.0.0.1").
  std::string boundAddress() const;
  /// "http://HOST:PORT/" ("https://" with TLS; IPv6 hosts in brackets).
  std::string url() const;
  /// The URL to open: url() with "?token=TOKEN" when there is a token.
  std::string openUrl() const;

  /// Accepts connections on a background thread; returns once it does.
  void start();
  /// Stops accepting, finishes the requests in progress, fails pending jobs and waits for
  /// running ones. Idempotent; callable from any thread but not from a signal handler.
  void stop();
  /// start(), then waits until a SIGINT or SIGTERM (core/stop.h; the caller installs the
  /// handlers) and stop()s. Returns the signal.
  int runUntilStopSignal();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace inet::studio
