// interiornet studio: the interactive designer (the paper's ViSim) as a web page served by this
// binary (src/studio/). This file only parses options.
#include <csignal>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "assets/catalog_library.h"
#include "common.h"
#include "core/error.h"
#include "studio/server.h"
#include "studio/studio_layout.h"

namespace inet::app {
namespace {

struct StudioArgs {
  SceneSource scene;
  studio::StudioOptions opt;
  std::string web;
  std::vector<std::string> data;  ///< NAME=DIR
  size_t max_body_kib = 1024;
  bool no_token = false;
};

/// 128 random bits as 32 hex digits: the access token when none is given.
std::string randomToken() {
  std::random_device rd;
  std::string out;
  for (int i = 0; i < 4; ++i) out += fmt::format("{:08x}", rd());
  return out;
}

/// "--data NAME=DIR" into the options' data roots.
void addDataRoots(const std::vector<std::string>& specs, studio::StudioOptions& opt) {
  for (const std::string& s : specs) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
      throw InputError("", "--data", "'" + s + "' is not NAME=DIR");
    const std::string name = s.substr(0, eq);
    if (opt.data_roots.count(name) != 0)
      throw InputError("", "--data", "the name '" + name + "' is given twice");
    opt.data_roots[name] = s.substr(eq + 1);
  }
}

void runStudio(StudioArgs a) {
  installStopHandlers();  // a stop signal while the layout loads ends the studio right after
  addDataRoots(a.data, a.opt);
  if (!a.web.empty()) a.opt.web_root = a.web;
  a.opt.serve_out = true;  // the page shows what its jobs wrote (/api/files/out/...)
  if (a.max_body_kib < 1 || a.max_body_kib > 1024 * 1024)
    throw InputError("", "--max-body", "must be in 1..1048576 KiB");
  a.opt.max_body_bytes = a.max_body_kib * 1024;
  if (a.no_token && !a.opt.token.empty())
    throw InputError("", "--no-token", "--token and --no-token together");
  if (!a.no_token && a.opt.token.empty()) a.opt.token = randomToken();
  if (a.scene.isDefault()) a.scene.default_apartment = catalogsAvailable();
  std::fprintf(stderr, "studio: loading %s\n",
               a.scene.isDefault()
                   ? (a.scene.default_apartment ? "builtin:apartment" : "builtin:room")
                   : a.scene.path.c_str());
  const auto layout = studio::loadStudioLayout(a.scene);
  studio::StudioServer server(a.opt, layout);
  std::printf("studio: serving %s (layout %s, loaded in %.1f s); Ctrl-C stops\n",
              server.openUrl().c_str(), layout->scene.name.c_str(), layout->load_s);
  const std::string query = a.opt.token.empty() ? "" : "?token=" + a.opt.token;
  if (!a.opt.allow_remote)
    std::printf(
        "studio: from another machine: ssh -L %d:localhost:%d THIS_HOST, then open "
        "%s://localhost:%d/%s\n",
        server.port(), server.port(), a.opt.tls_cert.empty() ? "http" : "https", server.port(),
        query.c_str());
  std::fflush(stdout);  // a script or test reads the port from a pipe
  const int sig = server.runUntilStopSignal();
  std::printf("studio: stopped by %s\n", sig == SIGINT    ? "SIGINT"
                                         : sig == SIGTERM ? "SIGTERM"
                                                          : "a signal");
}

}  // namespace

void registerStudio(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "studio",
      "Serve the studio, the interactive designer (the paper's ViSim), as a web page: the "
      "layout in 3D and as a floor plan, keyframed camera paths checked against the free "
      "space, trajectory export and sequence generation (docs/studio.md). Runs until Ctrl-C "
      "or SIGTERM (exit 0)");
  cmd->footer(
      "Only this machine can connect by default (127.0.0.1). To use the studio on a "
      "workstation or cluster node from your laptop, tunnel the port over SSH instead of "
      "opening it:\n"
      "  laptop$ ssh -L 8080:localhost:8080 node   # then, on node: interiornet studio\n"
      "  and open http://localhost:8080/ in the laptop's browser.\n"
      "--allow-remote serves other machines directly: the studio has no login, so anyone who "
      "reaches the port and has the token can read the --data folders and start jobs; without "
      "--tls-cert/--tls-key it has no encryption either (the token crosses the network in "
      "clear). Other users of a shared machine can reach its loopback too: the "
      "access token (printed in the URL, kept by the browser as a cookie) keeps them out.");
  auto a = std::make_shared<StudioArgs>();
  addSceneFlags(*cmd, a->scene,
                "the built-in apartment (builtin:apartment) where the Sweet Home 3D catalogs are "
                "installed, else the built-in furnished room (builtin:room)");
  cmd->add_option("--port", a->opt.port, "TCP port; 0 = any free one, printed (default 8080)");
  cmd->add_option("--host", a->opt.host,
                  "address to listen on (default 127.0.0.1); anything but the loopback needs "
                  "--allow-remote");
  cmd->add_flag("--allow-remote", a->opt.allow_remote,
                "allow --host to be an address other machines reach (prints a warning; prefer "
                "an SSH tunnel)");
  cmd->add_option("--web", a->web,
                  "folder of the page's files (default: the page the build bundled, else "
                  "share/interiornet/studio/web; $INET_STUDIO_WEB overrides)");
  cmd->add_option("--out", a->opt.out_dir,
                  "where \"generate sequence\" writes: <out>/<layout name>/<sequence>/, as "
                  "generate --out (default out); served read-only at /api/files/out/...");
  cmd->add_option("--data", a->data,
                  "NAME=DIR: serve DIR's files read-only at /api/files/NAME/... (repeatable; "
                  "nothing else on disk is served, not even the layout's folder unless given)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--threads", a->opt.threads,
                  "connections served at once (default 32); previews are computed as many at "
                  "a time as the machine has cores");
  cmd->add_option("--max-body", a->max_body_kib, "largest request body in KiB (default 1024)");
  cmd->add_flag("--log", a->opt.log_requests, "print one line per request on stderr");
  cmd->add_option("--token", a->opt.token,
                  "the access token every request must carry (16..128 letters, digits, - and "
                  "_); default: a random one, in the URL printed");
  cmd->add_option("--tls-cert", a->opt.tls_cert,
                  "serve HTTPS with this PEM certificate (chain); needs --tls-key. For "
                  "--allow-remote: the token and the data then cross the network encrypted");
  cmd->add_option("--tls-key", a->opt.tls_key,
                  "the certificate's PEM private key (unencrypted; keep it readable by you only)");
  cmd->add_flag("--no-token", a->no_token,
                "no access token: anyone who can reach the port (every user of this machine) "
                "can use the studio");
  cmd->callback([a] { runStudio(*a); });
}

}  // namespace inet::app
