// insitu modes
//
// Prints the integrators, the irradiance modes and the tone maps as Markdown tables, made from the
// code's own tables (scene/mode_tables.h): what each does, what it uses, and its parameters with
// their defaults. docs/cli.md holds this output.
#include <cstdio>

#include "commands.h"
#include "scene/mode_tables.h"

namespace insitu {

Command add_modes_command(CLI::App& app) {
  app.add_subcommand("modes", "list the integrators, irradiance modes and tone maps, with their parameters");
  return [] {
    std::fputs(mode_tables().c_str(), stdout);
    return 0;
  };
}

}  // namespace insitu
