#include "scene/mode_tables.h"

#include <fmt/format.h>

#include "integrators/registry.h"
#include "light/irradiance.h"
#include "output/settings.h"

namespace insitu {
namespace {

const char* yes_no(bool b) { return b ? "yes" : "no"; }

// "`max_depth` 5, …" from the parameters an integrator reads from an empty render object.
std::string defaults_of(const IntegratorEntry& e) {
  const JsonBlock empty{json::object(), "", "$.render"};
  IntegratorParams params(empty, e.name);
  const json read = e.read_params(params);
  std::string out;
  for (const auto& [key, value] : read.items())
    out += fmt::format("{}`{}` {}", out.empty() ? "" : ", ", key,
                       value.is_string() ? value.get<std::string>() : value.dump());
  return out.empty() ? "—" : out;
}

}  // namespace

std::string integrator_table() {
  std::string t =
      "| integrator | what it does | catches shadows (local_scene) | room box | noise falls as 1/√spp | "
      "parameters (defaults) |\n|---|---|---|---|---|---|\n";
  for (const IntegratorEntry& e : integrator_registry())
    t += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", e.name, e.summary, yes_no(e.uses.local_scene),
                     yes_no(e.uses.room_box), yes_no(e.uses.monte_carlo), defaults_of(e));
  return t;
}

std::string irradiance_mode_table() {
  std::string t = "| mode | what it computes |\n|---|---|\n";
  for (const auto& [mode, name] : kIrradianceModes)
    t += fmt::format("| `{}` | {} |\n", name, irradiance_mode_summary(mode));
  return t;
}

std::string tonemap_table() {
  std::string t = "| operator | what it does | parameters (defaults) |\n|---|---|---|\n";
  for (const auto& [op, name] : kToneMaps) {
    std::string params;
    if (reads_key(op)) params = fmt::format("`key` {:g}", default_key(op));
    if (reads_bias(op)) params += fmt::format(", `bias` {:g}", ToneMapSettings{}.bias);
    t += fmt::format("| `{}`{} | {} | {} |\n", name, op == ToneMapSettings{}.op ? " (default)" : "",
                     tonemap_summary(op), params.empty() ? "—" : params);
  }
  return t;
}

std::string mode_tables() {
  return "Integrators (`render.integrator`, `--integrator`):\n\n" + integrator_table() +
         "\nIrradiance modes of the `irradiance` integrator (`render.irradiance`, `--irradiance`):\n\n" +
         irradiance_mode_table() + "\nTone maps (`output.tonemap`, `--tonemap`, `--key`):\n\n" + tonemap_table();
}

}  // namespace insitu
