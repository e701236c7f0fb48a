#include "studio/server.h"

#include <arpa/inet.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <semaphore>
#include <set>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/stop.h"
#include "studio/design_api.h"
#include "studio/frame_preview.h"
#include "studio/job_queue.h"
#include "studio/layout_glb.h"
#include "studio/loopback.h"
#include "studio/safe_path.h"
#include "studio/sequence_api.h"
#include "studio/trajectory_api.h"

namespace inet::studio {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path defaultWebRoot() {
  if (const char* env = std::getenv("INET_STUDIO_WEB"); env != nullptr && *env != '\0') return env;
  std::error_code ec;
  const fs::path built = INET_STUDIO_WEB_BUILD_PATH;
  if (fs::is_regular_file(built / "index.html", ec)) return built;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share/interiornet/studio/web";
    if (fs::is_regular_file(installed / "index.html", ec)) return installed;
  }
  return INET_STUDIO_WEB_SOURCE_PATH;  // the page saying how to build the page
}

namespace {

/// The listening socket of an httplib server, plain or TLS.
class ServerSocket {
 public:
  virtual ~ServerSocket() = default;
  /// The socket bound, to report its address; -1 when there is none.
  virtual int listeningSocket() const = 0;
  /// Closes a socket that was bound but never served (httplib's stop() only stops a running
  /// server).
  virtual void closeUnserved() = 0;
};

/// httplib's server (httplib::Server, or httplib::SSLServer for HTTPS) with its listening
/// socket visible.
template <class Base>
class HttpServer final : public Base, public ServerSocket {
 public:
  using Base::Base;
  int listeningSocket() const override { return this->svr_sock_; }
  void closeUnserved() override {
    if (this->is_running()) return;
    const int fd = this->svr_sock_.exchange(-1);
    if (fd >= 0) ::close(fd);
  }
};

/// The local address of socket `fd` as text ("127.0.0.1", "::1"), or "" if it has none.
std::string socketAddress(int fd) {
  sockaddr_storage addr{};
  socklen_t len = sizeof addr;
  if (fd < 0 || ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) return "";
  const void* a =
      addr.ss_family == AF_INET6
          ? static_cast<const void*>(&reinterpret_cast<const sockaddr_in6*>(&addr)->sin6_addr)
          : static_cast<const void*>(&reinterpret_cast<const sockaddr_in*>(&addr)->sin_addr);
  char text[INET6_ADDRSTRLEN] = "";
  return ::inet_ntop(addr.ss_family, a, text, sizeof text) != nullptr ? text : "";
}

std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

void sendJson(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void sendError(httplib::Response& res, int status, const std::string& message,
               const std::string& file = "", const std::string& field = "") {
  sendJson(res, status, {{"error", oneLine(message)}, {"file", file}, {"field", field}});
}

/// The value of cookie `name` in the request's Cookie headers, or "".
std::string cookieValue(const httplib::Request& req, const std::string& name) {
  for (size_t i = 0; i < req.get_header_value_count("Cookie"); ++i) {
    const std::string header = req.get_header_value("Cookie", i);
    size_t at = 0;
    while (at < header.size()) {
      const size_t end = std::min(header.find(';', at), header.size());
      std::string pair = header.substr(at, end - at);
      pair.erase(0, pair.find_first_not_of(' '));
      if (pair.rfind(name + "=", 0) == 0) return pair.substr(name.size() + 1);
      at = end + 1;
    }
  }
  return "";
}

/// a == b in time that depends on the lengths only.
bool sameSecret(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (size_t i = 0; i < a.size(); ++i)
    diff |= static_cast<unsigned char>(a[i] ^ (i < b.size() ? b[i] : 0));
  return diff == 0;
}

/// `target` with the value of any token= query parameter replaced by "...", for the log.
std::string redactToken(std::string target) {
  for (size_t at = target.find("token="); at != std::string::npos;
       at = target.find("token=", at + 6)) {
    const size_t end = std::min(target.find('&', at), target.size());
    target.replace(at + 6, end - at - 6, "...");
  }
  return target;
}

/// The path part of the raw request target (still percent-encoded).
std::string rawPath(const httplib::Request& req) {
  return req.target.substr(0, req.target.find('?'));
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Serves `file` (already resolved) in 64 KiB pieces, so a large glTF does not sit in memory
/// once per request.
void sendFile(httplib::Response& res, const fs::path& file) {
  auto in = std::make_shared<std::ifstream>(file, std::ios::binary);
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (!*in || ec) return sendError(res, 404, "cannot read the file");
  res.status = 200;
  res.set_content_provider(static_cast<size_t>(size), contentTypeFor(file).c_str(),
                           [in](size_t offset, size_t length, httplib::DataSink& sink) {
                             std::vector<char> buf(std::min<size_t>(length, 64 * 1024));
                             in->clear();
                             in->seekg(static_cast<std::streamoff>(offset));
                             in->read(buf.data(), static_cast<std::streamsize>(buf.size()));
                             const auto n = in->gcount();
                             return n > 0 && sink.write(buf.data(), static_cast<size_t>(n));
                           });
}

/// Methods whose bodies the studio reads itself, through httplib's content reader (so that a
/// chunked body is limited too): every other request's body httplib reads, without a limit when
/// chunked.
bool readsOwnBody(const std::string& method) {
  return method == "POST" || method == "PUT" || method == "PATCH" || method == "DELETE";
}

/// Requests refused before httplib reads their body (pre-routing). A body left unread is read
/// as the next request of the same connection, so only requests that normally have none are
/// refused here.
httplib::Server::HandlerResponse refuseBeforeReading(const httplib::Request& req,
                                                     httplib::Response& res) {
  using HR = httplib::Server::HandlerResponse;
  if (req.has_header("Transfer-Encoding") && !readsOwnBody(req.method)) {
    sendError(res, 411, req.method + " with a chunked body", "", "Transfer-Encoding");
    return HR::Handled;
  }
  // httplib itself routes only these; TRACE and CONNECT would get a bare 400
  static const std::set<std::string> known = {"GET",   "HEAD",   "POST",   "PUT",
                                              "PATCH", "DELETE", "OPTIONS"};
  if (known.count(req.method) == 0) {
    res.set_header("Allow", "GET, HEAD, POST");
    sendError(res, 405, req.method + " is not allowed");
    return HR::Handled;
  }
  return HR::Unhandled;
}

/// Holds one of `slots` for its lifetime.
class SlotGuard {
 public:
  explicit SlotGuard(std::counting_semaphore<1024>& slots) : slots_(slots) { slots_.acquire(); }
  ~SlotGuard() { slots_.release(); }
  SlotGuard(const SlotGuard&) = delete;
  SlotGuard& operator=(const SlotGuard&) = delete;

 private:
  std::counting_semaphore<1024>& slots_;
};

enum class BodyRead { Ok, TooLarge, Failed };

/// Reads a request's body through httplib's content reader, at most `max` bytes (httplib checks
/// a Content-Length against its own limit, the same, and reads and drops an oversized body; a
/// chunked one is cut off here).
BodyRead readBody(const httplib::Request& req, const httplib::Response& res,
                  const httplib::ContentReader& reader, size_t max, std::string& body) {
  bool too_large = false;
  auto keep = [&](const char* data, size_t n) {
    if (body.size() + n > max) {
      too_large = true;
      return false;
    }
    body.append(data, n);
    return true;
  };
  // a multipart body must be read as one (httplib would call a missing receiver); its parts
  // are kept only to be refused: no route takes them
  const bool ok = req.is_multipart_form_data()
                      ? reader([](const httplib::MultipartFormData&) { return true; }, keep)
                      : reader(keep);
  if (too_large || res.status == 413) return BodyRead::TooLarge;
  return ok ? BodyRead::Ok : BodyRead::Failed;
}

/// One request as a route sees it.
struct Call {
  const httplib::Request& req;
  const std::string& body;  ///< read with the size limit
  std::string rest;         ///< a prefix route's raw path after the prefix
};

using RouteHandler = std::function<void(const Call&, httplib::Response&)>;

struct Route {
  std::string method;  ///< GET (HEAD too) or POST
  std::string path;    ///< exact path, or the prefix of a prefix route (ending in '/')
  bool prefix = false;
  RouteHandler handler;
};

}  // namespace

struct StudioServer::Impl {
  StudioOptions opt;
  std::shared_ptr<const StudioLayout> layout;
  fs::path web_root;                      ///< canonical
  std::map<std::string, fs::path> roots;  ///< canonical
  std::unique_ptr<httplib::Server> http;
  ServerSocket* socket = nullptr;  ///< http's
  std::vector<Route> routes;
  std::unique_ptr<JobQueue> jobs;
  std::unique_ptr<LayoutGlb> glb;
  std::unique_ptr<FramePreviewer> previewer;
  std::unique_ptr<std::counting_semaphore<1024>> compute;
  std::thread listener;
  std::atomic<bool> stopped{false};
  int port = 0;
  const std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  void checkOptions();
  void makeHttp();
  bool checkToken(const httplib::Request& req, httplib::Response& res) const;
  void bind();
  void addRoutes();
  void configureHttp();
  void installHandlers();
  void dispatch(const httplib::Request& req, const std::string& body, httplib::Response& res);
  json parseBody(const std::string& body) const;

  void health(httplib::Response& res) const;
  void staticFile(const std::string& raw, httplib::Response& res) const;
  void dataFile(const std::string& rest, httplib::Response& res) const;
  void preview(const std::string& body, httplib::Response& res);
  void submitJob(const std::string& body, httplib::Response& res);
  void submitSequence(const std::string& body, httplib::Response& res);
  void queued(const std::optional<std::string>& id, httplib::Response& res);
  void designPath(const std::string& body, httplib::Response& res);
  void designExport(const std::string& body, httplib::Response& res);
  void previewFrame(const std::string& body, httplib::Response& res);
  void jobStatus(const std::string& id, httplib::Response& res) const;
  void cancelJob(const std::string& id, httplib::Response& res);
  void jobEvents(const std::string& id, httplib::Response& res);
  std::atomic<int> streams{0};  ///< progress streams open (jobEvents)
};

void StudioServer::Impl::checkOptions() {
  auto range = [](int v, int lo, int hi, const char* field) {
    if (v < lo || v > hi) throw InputError("", field, fmt::format("must be in {}..{}", lo, hi));
  };
  range(opt.port, 0, 65535, "--port");
  range(opt.threads, 1, 1024, "--threads");
  range(opt.compute_slots, 0, 1024, "compute_slots");
  range(opt.job_workers, 1, 64, "job_workers");
  range(opt.max_jobs, 1, 100000, "max_jobs");
  range(opt.max_preview_frames, 1, 10'000'000, "max_preview_frames");
  range(opt.max_job_frames, 1, 10'000'000, "max_job_frames");
  if (opt.max_body_bytes < 64) throw InputError("", "max_body_bytes", "must be >= 64");
  if (!opt.token.empty() &&
      (opt.token.size() < 16 || opt.token.size() > 128 ||
       opt.token.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                   "0123456789-_") != std::string::npos))
    throw InputError("", "--token", "use 16..128 letters, digits, '-' and '_'");
  if (!opt.allow_remote && !isLoopbackHost(opt.host))
    throw InputError("", "--host",
                     fmt::format("'{}' is not a loopback address; serving other machines needs "
                                 "--allow-remote (the studio has no login and no encryption: "
                                 "prefer an SSH tunnel, see --help)",
                                 opt.host));
  std::error_code ec;
  const fs::path web = opt.web_root.empty() ? defaultWebRoot() : opt.web_root;
  web_root = fs::canonical(web, ec);
  if (ec || !fs::is_directory(web_root))
    throw InputError(web.string(), "--web", "the studio's web folder does not exist");
  if (opt.serve_out && opt.data_roots.count("out") == 0) {
    fs::create_directories(opt.out_dir, ec);
    opt.data_roots["out"] = opt.out_dir;
  }
  for (const auto& [name, dir] : opt.data_roots) {
    if (name.empty() ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                               "0123456789-_") != std::string::npos)
      throw InputError(dir.string(), "--data",
                       fmt::format("root name '{}': use letters, digits, '-' and '_'", name));
    // resolved once, now: replacing a symlinked root later does not move what is served
    const fs::path canonical = fs::canonical(dir, ec);
    if (ec || !fs::is_directory(canonical))
      throw InputError(dir.string(), "--data", "not a folder");
    roots[name] = canonical;
  }
}

/// A plain HTTP server, or HTTPS with the certificate and key of tls_cert and tls_key
/// (both or neither: InputError naming the flag; one that httplib cannot load: the same).
void StudioServer::Impl::makeHttp() {
  if (opt.tls_cert.empty() != opt.tls_key.empty())
    throw InputError("", opt.tls_cert.empty() ? "--tls-cert" : "--tls-key",
                     "HTTPS needs both --tls-cert and --tls-key");
  if (opt.tls_cert.empty()) {
    auto plain = std::make_unique<HttpServer<httplib::Server>>();
    socket = plain.get();
    http = std::move(plain);
    return;
  }
  for (const auto& [file, flag] :
       {std::pair{opt.tls_cert, "--tls-cert"}, {opt.tls_key, "--tls-key"}})
    if (!fs::is_regular_file(file)) throw InputError(file.string(), flag, "no such file");
  auto tls =
      std::make_unique<HttpServer<httplib::SSLServer>>(opt.tls_cert.c_str(), opt.tls_key.c_str());
  if (!tls->is_valid())
    throw InputError(opt.tls_cert.string(), "--tls-cert",
                     "cannot use it with --tls-key " + opt.tls_key.string() +
                         " (PEM certificate and its unencrypted PEM private key)");
  socket = tls.get();
  http = std::move(tls);
}

void StudioServer::Impl::bind() {
  if (opt.port == 0) {
    port = http->bind_to_any_port(opt.host);
    if (port <= 0) port = 0;
  } else if (http->bind_to_port(opt.host, opt.port)) {
    port = opt.port;
  }
  if (port == 0)
    throw InputError("", opt.port == 0 ? "--host" : "--port",
                     fmt::format("cannot listen on {}:{} (in use, or not an address of this "
                                 "machine)",
                                 opt.host, opt.port));
  // httplib listens with a backlog of 5: a burst of connections (a page loading its assets, or
  // 50 clients at once) overflows it and the kernel drops some. listen() again sets a new one.
  ::listen(socket->listeningSocket(), SOMAXCONN);
  // the kernel's word on what was bound, whatever the name resolved to
  const std::string text = socketAddress(socket->listeningSocket());
  if (!opt.allow_remote && !isLoopbackLiteral(text)) {
    socket->closeUnserved();
    throw InputError("", "--host",
                     fmt::format("'{}' bound {}, not a loopback address", opt.host, text));
  }
  if (opt.allow_remote && !isLoopbackLiteral(text) && opt.tls_cert.empty())
    std::fprintf(stderr,
                 "warning: studio: listening on %s port %d, reachable from other machines: the "
                 "studio has no login and no encryption (the token crosses the network in clear), "
                 "and anyone who reaches the port can read the data folders and start jobs (an "
                 "SSH tunnel keeps it private, or --tls-cert/--tls-key encrypt it: see --help)\n",
                 text.c_str(), port);
  else if (opt.allow_remote && !isLoopbackLiteral(text))
    std::fprintf(stderr,
                 "warning: studio: listening on %s port %d (HTTPS), reachable from other "
                 "machines: the access token is the only key; anyone who has it can read the "
                 "data folders and start jobs\n",
                 text.c_str(), port);
}

json StudioServer::Impl::parseBody(const std::string& body) const {
  try {
    return json::parse(body);
  } catch (const json::parse_error& e) {
    throw InputError("request body", "", std::string("malformed JSON: ") + e.what());
  }
}

void StudioServer::Impl::health(httplib::Response& res) const {
  sendJson(res, 200,
           {{"status", "ok"},
            {"version", INET_VERSION},
            {"layout", layout->scene.name},
            {"jobs", {{"running", jobs->running()}, {"stored", jobs->list().size()}}},
            {"uptime_s", std::round(secondsSince(started) * 10) / 10}});
}

void StudioServer::Impl::staticFile(const std::string& raw, httplib::Response& res) const {
  const std::string rel = raw == "/" ? "index.html" : raw.substr(1);
  const ResolvedPath p = resolveBelowRoot(web_root, rel);
  if (!p.ok()) return sendError(res, p.httpStatus(), pathRefusalName(p.refusal));
  sendFile(res, p.path);
}

void StudioServer::Impl::dataFile(const std::string& rest, httplib::Response& res) const {
  const size_t slash = rest.find('/');
  const std::string name = rest.substr(0, slash);
  const auto root = roots.find(name);
  if (root == roots.end()) {
    std::string names;
    for (const auto& [n, dir] : roots) names += (names.empty() ? "" : ", ") + n;
    return sendError(
        res, 404,
        fmt::format("no data root '{}' ({})", oneLine(name), names.empty() ? "none given" : names));
  }
  const ResolvedPath p =
      resolveBelowRoot(root->second, slash == std::string::npos ? "" : rest.substr(slash + 1));
  if (!p.ok()) return sendError(res, p.httpStatus(), pathRefusalName(p.refusal));
  sendFile(res, p.path);
}

void StudioServer::Impl::preview(const std::string& body, httplib::Response& res) {
  const TrajectoryRequest r = parseTrajectoryRequest(parseBody(body), opt.max_preview_frames);
  // previews are computed a few at a time; the other workers stay free for quick requests
  json out;
  {
    SlotGuard slot(*compute);
    out = runTrajectoryRequest(*layout, r);
  }
  sendJson(res, 200, out);
}

void StudioServer::Impl::submitJob(const std::string& body, httplib::Response& res) {
  const TrajectoryRequest r = parseTrajectoryRequest(parseBody(body), opt.max_job_frames);
  auto layout_ref = layout;
  const auto id = jobs->submit("trajectory", [layout_ref, r](JobContext& ctx) {
    ctx.progress(0.0, fmt::format("simulating {} frames", r.frames));
    return runTrajectoryRequest(*layout_ref, r);
  });
  queued(id, res);
}

void StudioServer::Impl::queued(const std::optional<std::string>& id, httplib::Response& res) {
  if (!id)
    return sendError(
        res, 503,
        fmt::format("{} jobs are stored and none has finished; wait for one", opt.max_jobs));
  res.set_header("Location", "/api/jobs/" + *id);
  sendJson(res, 202, {{"id", *id}, {"state", "pending"}, {"status_url", "/api/jobs/" + *id}});
}

void StudioServer::Impl::submitSequence(const std::string& body, httplib::Response& res) {
  auto req = std::make_shared<SequenceRequest>(
      parseSequenceRequest(parseBody(body), *layout, opt.out_dir));
  queued(jobs->submit("sequence", [req](JobContext& ctx) { return runSequenceRequest(*req, ctx); }),
         res);
}

void StudioServer::Impl::designPath(const std::string& body, httplib::Response& res) {
  const json request = parseBody(body);
  checkDesignKeys(request, {});
  const DesignRequest r = parseDesignRequest(request);
  json out;
  {
    SlotGuard slot(*compute);
    out = runDesignRequest(*layout, r);
  }
  sendJson(res, 200, out);
}

void StudioServer::Impl::designExport(const std::string& body, httplib::Response& res) {
  const json request = parseBody(body);
  checkDesignKeys(request, {"format"});
  const DesignRequest r = parseDesignRequest(request);
  if (!request.contains("format") || !request.at("format").is_string())
    throw InputError("", "format", "must be a trajectory format name (tum, euroc, ...)");
  const DesignExport e = exportDesign(r, request.at("format").get<std::string>());
  res.status = 200;
  res.set_header("Content-Disposition", "attachment; filename=\"" + e.file_name + "\"");
  res.set_content(e.text, e.content_type);
}

void StudioServer::Impl::jobStatus(const std::string& id, httplib::Response& res) const {
  const auto s = jobs->status(id);
  if (!s) return sendError(res, 404, fmt::format("no job '{}'", oneLine(id)));
  sendJson(res, 200, s->toJson());
}

void StudioServer::Impl::previewFrame(const std::string& body, httplib::Response& res) {
  const FramePreviewRequest r = parseFramePreview(parseBody(body));
  std::string png;
  {
    SlotGuard slot(*compute);
    png = previewer->png(r);
  }
  res.status = 200;
  res.set_content(png, "image/png");
}

/// GET /api/jobs/<id>/events: the job's status as server-sent events, one event each time it
/// changes state, progress or message (checked every 50 ms), a comment every second otherwise,
/// until it has finished. Each stream holds an HTTP worker, so at most a quarter of them stream at
/// once (503 beyond).
void StudioServer::Impl::jobEvents(const std::string& id, httplib::Response& res) {
  if (!jobs->status(id)) return sendError(res, 404, fmt::format("no job '{}'", oneLine(id)));
  const int max_streams = std::max(1, opt.threads / 4);
  if (streams.fetch_add(1) >= max_streams) {
    --streams;
    return sendError(res, 503,
                     fmt::format("{} progress streams are open; poll /api/jobs/{} instead",
                                 max_streams, oneLine(id)));
  }
  auto last = std::make_shared<std::string>();
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, id, last](size_t, httplib::DataSink& sink) {
        for (int i = 0; i < 20 && !stopped; ++i) {
          const auto s = jobs->status(id);
          if (!s) break;  // forgotten (the store is bounded)
          // a change of state, progress or message (elapsed_ms alone changes all the time)
          const std::string key =
              fmt::format("{}|{}|{}", jobStateName(s->state), s->progress, s->message);
          if (key != *last) {
            *last = key;
            const std::string data = "data: " + s->toJson().dump() + "\n\n";
            if (!sink.write(data.data(), data.size())) return false;
            if (s->state != JobState::Pending && s->state != JobState::Running) sink.done();
            return true;
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        if (stopped || !jobs->status(id)) {
          sink.done();
          return true;
        }
        static const std::string ping = ": ping\n\n";
        return sink.write(ping.data(), ping.size());
      },
      [this](bool) { --streams; });
}

void StudioServer::Impl::cancelJob(const std::string& id, httplib::Response& res) {
  const JobQueue::Cancel c = jobs->cancel(id);
  if (c == JobQueue::Cancel::NotFound)
    return sendError(res, 404, fmt::format("no job '{}'", oneLine(id)));
  const JobStatus s = *jobs->status(id);
  if (c == JobQueue::Cancel::Finished)
    return sendError(res, 409,
                     fmt::format("job '{}' has finished ({})", id, jobStateName(s.state)));
  sendJson(res, c == JobQueue::Cancel::Removed ? 200 : 202, s.toJson(false));
}

void StudioServer::Impl::addRoutes() {
  auto get = [this](std::string path, bool prefix, RouteHandler h) {
    routes.push_back({"GET", std::move(path), prefix, std::move(h)});
  };
  get("/api/health", false, [this](auto&, auto& res) { health(res); });
  get("/api/layout", false, [this](auto&, auto& res) {
    json j = layout->summary;
    j["load_s"] = std::round(layout->load_s * 1000) / 1000;
    sendJson(res, 200, j);
  });
  get("/api/files", false, [this](auto&, auto& res) {
    json names = json::array();
    for (const auto& [name, dir] : roots) names.push_back(name);
    sendJson(res, 200, {{"roots", names}});
  });
  get("/api/files/", true, [this](const Call& c, auto& res) { dataFile(c.rest, res); });
  get("/api/jobs", false, [this](auto&, auto& res) {
    json list = json::array();
    for (const JobStatus& s : jobs->list()) list.push_back(s.toJson(false));
    sendJson(res, 200, {{"jobs", list}});
  });
  get("/api/jobs/", true, [this](const Call& c, auto& res) {
    const std::string suffix = "/events";
    if (c.rest.size() > suffix.size() &&
        c.rest.compare(c.rest.size() - suffix.size(), suffix.size(), suffix) == 0)
      return jobEvents(c.rest.substr(0, c.rest.size() - suffix.size()), res);
    jobStatus(c.rest, res);
  });
  routes.push_back({"POST", "/api/trajectory/preview", false,
                    [this](const Call& c, auto& res) { preview(c.body, res); }});
  routes.push_back({"POST", "/api/jobs/trajectory", false,
                    [this](const Call& c, auto& res) { submitJob(c.body, res); }});
  routes.push_back(
      {"DELETE", "/api/jobs/", true, [this](const Call& c, auto& res) { cancelJob(c.rest, res); }});
  routes.push_back({"POST", "/api/jobs/sequence", false,
                    [this](const Call& c, auto& res) { submitSequence(c.body, res); }});
  routes.push_back({"POST", "/api/design/path", false,
                    [this](const Call& c, auto& res) { designPath(c.body, res); }});
  routes.push_back({"POST", "/api/design/imu", false, [this](const Call& c, auto& res) {
                      const json request = parseBody(c.body);
                      SlotGuard slot(*compute);
                      sendJson(res, 200, runImuRequest(request));
                    }});
  routes.push_back({"POST", "/api/preview/frame", false,
                    [this](const Call& c, auto& res) { previewFrame(c.body, res); }});
  routes.push_back({"POST", "/api/design/export", false,
                    [this](const Call& c, auto& res) { designExport(c.body, res); }});
  // ?level=N: the plan of floor level N (default 0, the lowest)
  get("/api/layout/plan", false, [this](const Call& c, auto& res) {
    const std::string text = c.req.has_param("level") ? c.req.get_param_value("level") : "0";
    const size_t n = layout->plans.size();
    if (text.empty() || text.size() > 3 ||
        text.find_first_not_of("0123456789") != std::string::npos || std::stoul(text) >= n)
      return sendError(res, 400,
                       fmt::format("level: must be in 0..{}, not '{}'", n - 1, oneLine(text)), "",
                       "level");
    sendJson(res, 200, layout->plans[std::stoul(text)]);
  });
  get("/api/layout.glb", false, [this](auto&, auto& res) { sendFile(res, glb->path()); });
}

/// False (and the response made) unless the request carries the access token. A request that
/// brings it as ?token= gets the cookie; a page request is then sent to its path without it.
bool StudioServer::Impl::checkToken(const httplib::Request& req, httplib::Response& res) const {
  if (opt.token.empty()) return true;
  const std::string auth = req.get_header_value("Authorization");
  const bool query = req.has_param("token");
  const std::string given = query                           ? req.get_param_value("token")
                            : auth.rfind("Bearer ", 0) == 0 ? auth.substr(7)
                                                            : cookieValue(req, "inet_studio_token");
  if (!sameSecret(given, opt.token)) {
    sendError(res, 401,
              given.empty() ? "this studio needs its access token: open the URL it printed "
                              "(.../?token=...) or send Authorization: Bearer TOKEN"
                            : "wrong access token",
              "", "token");
    return false;
  }
  if (!query) return true;
  // over HTTPS the browser sends the cookie back over HTTPS only
  res.set_header("Set-Cookie", "inet_studio_token=" + opt.token +
                                   "; Path=/; HttpOnly; SameSite=Strict" +
                                   (opt.tls_cert.empty() ? "" : "; Secure"));
  const std::string raw = rawPath(req);
  if (req.method == "GET" && raw.rfind("/api/", 0) != 0) {  // keep the token out of the history
    res.set_redirect(raw, 303);
    return false;
  }
  return true;
}

void StudioServer::Impl::dispatch(const httplib::Request& req, const std::string& body,
                                  httplib::Response& res) {
  if (!opt.allow_remote && !isLoopbackHostHeader(req.get_header_value("Host")))
    return sendError(res, 403,
                     fmt::format("Host '{}' is not a loopback name; the studio answers only to "
                                 "localhost (see --allow-remote)",
                                 oneLine(req.get_header_value("Host"))),
                     "", "Host");
  if (!checkToken(req, res)) return;
  const std::string raw = rawPath(req);
  const std::string method = req.method == "HEAD" ? "GET" : req.method;
  const bool api = raw == "/api" || raw.rfind("/api/", 0) == 0;
  if (!api) {  // static assets: GET only
    if (method != "GET") {
      res.set_header("Allow", "GET, HEAD");
      return sendError(res, 405, req.method + " is not allowed here (GET)");
    }
    return staticFile(raw, res);
  }
  const Route* match = nullptr;
  std::string allow;
  for (const Route& r : routes) {
    const bool hit =
        r.prefix ? raw.size() > r.path.size() && raw.rfind(r.path, 0) == 0 : raw == r.path;
    if (!hit) continue;
    if (allow.find(r.method) == std::string::npos)
      allow += (allow.empty() ? "" : ", ") + r.method + (r.method == "GET" ? ", HEAD" : "");
    if (r.method == method && match == nullptr) match = &r;
  }
  if (allow.empty()) return sendError(res, 404, "no such route: " + oneLine(raw));
  if (match == nullptr) {
    res.set_header("Allow", allow);
    return sendError(res, 405, fmt::format("{} is not allowed on {} ({})", req.method, raw, allow));
  }
  if (method == "POST") {
    const std::string type = req.get_header_value("Content-Type");
    if (type.substr(0, type.find(';')) != "application/json")
      return sendError(res, 415, "the body must be JSON (Content-Type: application/json)", "",
                       "Content-Type");
  }
  try {
    match->handler(Call{req, body, match->prefix ? raw.substr(match->path.size()) : ""}, res);
  } catch (const InputError& e) {
    sendError(res, 400, e.what(), e.file(), e.field());
  }
}

void StudioServer::Impl::configureHttp() {
  const int threads = opt.threads;
  http->new_task_queue = [threads] {
    return new httplib::ThreadPool(static_cast<size_t>(threads));
  };
  http->set_payload_max_length(opt.max_body_bytes);
  // httplib's default sets SO_REUSEPORT, which lets a second server bind the same port and
  // share its connections; SO_REUSEADDR only allows a restart over TIME_WAIT
  http->set_socket_options([](int sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  http->set_read_timeout(10, 0);
  http->set_write_timeout(10, 0);
  http->set_keep_alive_timeout(5);
  http->set_default_headers({{"X-Content-Type-Options", "nosniff"},
                             {"X-Frame-Options", "DENY"},
                             {"Referrer-Policy", "no-referrer"},
                             {"Cache-Control", "no-store"},
                             {"Content-Security-Policy",
                              "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; "
                              "connect-src 'self' blob:; img-src 'self' data: blob:; "
                              "style-src 'self' 'unsafe-inline'; frame-ancestors 'none'; "
                              "base-uri 'none'; form-action 'self'"}});
}

void StudioServer::Impl::installHandlers() {
  using HR = httplib::Server::HandlerResponse;
  http->set_pre_routing_handler(refuseBeforeReading);
  // every route goes through dispatch(), once the body is read (and size-checked)
  const char* any = "[\\s\\S]*";  // '.' would not match a decoded newline
  const httplib::Server::Handler plain =
      [this](const httplib::Request& req, httplib::Response& res) { dispatch(req, req.body, res); };
  // requests with a body (httplib: POST, PUT, PATCH, DELETE with one) come here instead
  const httplib::Server::HandlerWithContentReader reading =
      [this](const httplib::Request& req, httplib::Response& res,
             const httplib::ContentReader& reader) {
        std::string body;
        switch (readBody(req, res, reader, opt.max_body_bytes, body)) {
          case BodyRead::TooLarge:
            return sendError(res, 413,
                             fmt::format("the request body is over {} bytes", opt.max_body_bytes));
          case BodyRead::Failed:
            return sendError(res, 400, "the request body could not be read");
          case BodyRead::Ok:
            return dispatch(req, body, res);
        }
      };
  http->Get(any, plain);
  http->Options(any, plain);
  http->Post(any, plain).Post(any, reading);
  http->Put(any, plain).Put(any, reading);
  http->Patch(any, plain).Patch(any, reading);
  http->Delete(any, plain).Delete(any, reading);
  http->set_error_handler(httplib::Server::HandlerWithResponse(
      [this](const httplib::Request&, httplib::Response& res) -> HR {
        if (!res.body.empty()) return HR::Unhandled;  // one of ours, already JSON
        sendError(res, res.status,
                  res.status == 413
                      ? fmt::format("the request body is over {} bytes", opt.max_body_bytes)
                      : fmt::format("HTTP {}: the request was refused", res.status));
        return HR::Handled;
      }));
  http->set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
        std::string what = "unknown exception";
        try {
          std::rethrow_exception(ep);
        } catch (const std::exception& e) {
          what = e.what();
        } catch (...) {
        }
        sendError(res, 500, "internal error: " + what);
      });
  if (opt.log_requests)
    http->set_logger([](const httplib::Request& req, const httplib::Response& res) {
      std::fprintf(stderr, "studio: %s %s %d\n", req.method.c_str(),
                   oneLine(redactToken(req.target)).c_str(), res.status);
    });
}

StudioServer::StudioServer(StudioOptions opt, std::shared_ptr<const StudioLayout> layout)
    : impl_(std::make_unique<Impl>()) {
  INET_CHECK(layout != nullptr && layout->space != nullptr);
  impl_->opt = std::move(opt);
  impl_->layout = std::move(layout);
  impl_->checkOptions();
  impl_->makeHttp();
  const int slots = impl_->opt.compute_slots > 0
                        ? impl_->opt.compute_slots
                        : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  impl_->compute = std::make_unique<std::counting_semaphore<1024>>(std::min(slots, 1024));
  impl_->jobs =
      std::make_unique<JobQueue>(JobQueue::Options{impl_->opt.job_workers, impl_->opt.max_jobs});
  impl_->glb = std::make_unique<LayoutGlb>(impl_->layout);
  impl_->previewer = std::make_unique<FramePreviewer>(impl_->layout, impl_->glb->folder());
  impl_->addRoutes();
  impl_->configureHttp();
  impl_->installHandlers();
  impl_->bind();
}

StudioServer::~StudioServer() {
  stop();
}

int StudioServer::port() const {
  return impl_->port;
}

std::string StudioServer::boundAddress() const {
  return socketAddress(impl_->socket->listeningSocket());
}

std::string StudioServer::url() const {
  const std::string host = impl_->opt.host.find(':') != std::string::npos
                               ? "[" + impl_->opt.host + "]"
                               : impl_->opt.host;
  return fmt::format("{}://{}:{}/", impl_->opt.tls_cert.empty() ? "http" : "https", host,
                     impl_->port);
}

std::string StudioServer::openUrl() const {
  return impl_->opt.token.empty() ? url() : url() + "?token=" + impl_->opt.token;
}

void StudioServer::start() {
  if (impl_->listener.joinable() || impl_->stopped) return;
  impl_->listener = std::thread([this] { impl_->http->listen_after_bind(); });
  // stop() only stops a server that runs: wait until httplib says it does
  while (!impl_->http->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void StudioServer::stop() {
  if (impl_->stopped.exchange(true)) return;
  impl_->http->stop();
  if (impl_->listener.joinable()) impl_->listener.join();
  impl_->socket->closeUnserved();
  impl_->jobs->shutdown();
}

int StudioServer::runUntilStopSignal() {
  start();
  while (stopSignal() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  stop();
  return stopSignal();
}

}  // namespace inet::studio
