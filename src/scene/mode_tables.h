// The reference tables of what a render can be asked for — the integrators, the irradiance modes
// and the tone maps — made from the tables in the code (the integrators' registry,
// kIrradianceModes, kToneMaps) as Markdown. `insitu modes` prints them; docs/cli.md holds the same
// text between its "insitu modes" markers, and a test compares the two, so a mode added to the
// code fails it until the page is regenerated:
//   build/insitu modes   (then paste between the markers)
#pragma once
#include <string>

namespace insitu {

// | integrator | what it does | catches shadows | room box | noise | parameters (defaults) |
std::string integrator_table();
// | mode | what it computes |
std::string irradiance_mode_table();
// | operator | what it does | parameters (defaults) |
std::string tonemap_table();
// The three, each under a line naming the setting it is for.
std::string mode_tables();

}  // namespace insitu
