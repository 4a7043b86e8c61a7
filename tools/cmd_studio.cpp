// insitu studio SCENE [--port 8080]: the local web page over one scene (src/studio/studio_server.h).
// It prints the address to open, with the launch's token (src/studio/request_guard.h). The first
// Ctrl-C (SIGINT, or SIGTERM) stops the server and a render under way, and the process exits 0; a
// second ends it at once.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

#include "commands.h"
#include "core/temp_files.h"
#include "studio/studio_server.h"

namespace insitu {
namespace {

struct StudioArgs {
  std::string scene;
  int port = 8080;
};

int run_studio(const StudioArgs& a) {
  StudioServer server({a.scene, a.port});
  server.bind();
  std::printf("insitu studio: %s  (%s; Ctrl-C stops it)\n", server.url().c_str(), a.scene.c_str());
  std::fflush(stdout);
  arm_graceful_stop(true);
  std::atomic<bool> served{false};
  // The signal handler only sets a flag (async-signal-safe); this thread turns it into a stop.
  std::thread watcher([&] {
    while (!served && !graceful_stop_flag()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    server.stop();
  });
  server.run();
  served = true;
  watcher.join();
  arm_graceful_stop(false);
  if (graceful_stop_flag()) std::fprintf(stderr, "insitu studio: stopped\n");
  return 0;
}

}  // namespace

Command add_studio_command(CLI::App& app) {
  auto a = std::make_shared<StudioArgs>();
  CLI::App* cmd = app.add_subcommand(
      "studio", "serve a web page on 127.0.0.1 to click the control points and check the calibration");
  cmd->add_option("scene", a->scene, "the scene file (its camera.points is the points.json the page edits)")
      ->required();
  cmd->add_option("--port", a->port, "the port on 127.0.0.1 (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  return [cmd, a] { return cmd->parsed() ? run_studio(*a) : -1; };
}

}  // namespace insitu
