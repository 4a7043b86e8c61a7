// insitu studio SCENE [--port 8080]: the local web page over one scene (src/studio/studio_server.h).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "studio/studio_server.h"

namespace insitu {
namespace {

struct StudioArgs {
  std::string scene;
  int port = 8080;
};

int run_studio(const StudioArgs& a) {
  StudioServer server({a.scene, a.port});
  const int port = server.bind();
  std::printf("insitu studio: http://127.0.0.1:%d/  (%s; Ctrl-C stops it)\n", port, a.scene.c_str());
  std::fflush(stdout);
  server.run();
  return 0;
}

}  // namespace

Command add_studio_command(CLI::App& app) {
  auto a = std::make_shared<StudioArgs>();
  CLI::App* cmd = app.add_subcommand("studio", "serve a web page on 127.0.0.1 to click the control points and check the calibration");
  cmd->add_option("scene", a->scene, "the scene file (its camera.points is the points.json the page edits)")->required();
  cmd->add_option("--port", a->port, "the port on 127.0.0.1 (0: any free port)")->check(CLI::Range(0, 65535))->capture_default_str();
  return [cmd, a] { return cmd->parsed() ? run_studio(*a) : -1; };
}

}  // namespace insitu
