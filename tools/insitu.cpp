// The insitu command line: a thin shell over the library (DESIGN.md "Layout"); one file per verb
// (cmd_*.cpp). Bad input: one line `insitu: error: <where>: <what>` on stderr, exit code 2,
// nothing written. Internal failure: exit code 1.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <malloc.h>

#include "commands.h"
#include "core/temp_files.h"

namespace {

// glibc's malloc gives large blocks back to the system when they are freed (mmap above a
// threshold that adapts up to 32 MiB, and a trim of the heap's top above 128 KiB), so each of a
// load's cube-sized samplers (10 MB for a 256² cube: light recovery builds one per clipped part)
// and each render's per-pixel sums is faulted in afresh: 0.9 s of system time in a 1-spp render of
// the demo. A process of insitu keeps them for reuse instead: blocks up to 32 MiB (glibc's
// largest threshold) come from the heap, and up to 1 GiB of free heap is kept. The demo at 1 spp:
// 3.7 s → 3.2 s wall, 0.85 s → 0.5 s system (docs/farm.md). Only the command-line program does
// this: the C API and the Python module leave their host's allocator alone.
void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace insitu;
  keep_freed_memory();
  install_interrupt_cleanup();  // an interrupted write leaves no temporary file
  // A file-size limit (`ulimit -f`) fails a write with EFBIG, which is then reported like a full
  // disk (exit 2, nothing written), instead of ending the process by SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"insitu: physically based insertion of 3D furniture into a photograph of a room"};
  app.set_version_flag("--version", std::string("insitu ") + INSITU_VERSION);
  app.require_subcommand(1);
  const std::vector<Command> commands = {add_render_command(app),         add_calibrate_command(app),
                                         add_cubemap_command(app),        add_irradiance_report_command(app),
                                         add_compare_command(app),        add_tradeoff_command(app),
                                         add_export_blender_command(app), add_merge_command(app),
                                         add_batch_command(app),          add_studio_command(app),
                                         add_modes_command(app)};
  // An unknown verb is named (CLI11 would say only that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::string verbs;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      known |= sub->get_name() == argv[1];
      verbs += (verbs.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "insitu: error: unknown verb '%s' (one of: %s; see insitu --help)\n", argv[1],
                   verbs.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    if (auto nl = msg.find('\n'); nl != std::string::npos) msg.resize(nl);
    std::fprintf(stderr, "insitu: error: %s (see insitu --help)\n", msg.c_str());
    return 2;
  }
  try {
    for (const Command& run : commands)
      if (const int rc = run(); rc >= 0) return rc;
  } catch (const InputError& e) {
    std::string msg = e.what();
    for (auto& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "insitu: error: %s\n", msg.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "insitu: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
