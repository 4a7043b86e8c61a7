#include <fmt/format.h>

#include "error.h"
#include "integrators/integrator.h"

namespace insitu {

std::unique_ptr<Integrator> make_realtime_integrator(const RenderInputs& inputs);
std::unique_ptr<Integrator> make_irradiance_integrator(const RenderInputs& inputs);
std::unique_ptr<Integrator> make_path_integrator(const RenderInputs& inputs);

const std::vector<IntegratorEntry>& integrator_registry() {
  static const std::vector<IntegratorEntry> table = {
      {"realtime", "legacy real-time path: base colour x face-blurred cube at the normal, no shadows",
       make_realtime_integrator, {}},
      {"irradiance", "Lambertian objects lit by an irradiance mode (render.irradiance), no visibility",
       make_irradiance_integrator, {/*local_scene*/ false, /*room_box*/ false, /*irradiance_mode*/ true, /*max_depth*/ false}},
      {"path", "path tracing of the objects with environment importance sampling and MIS (shadows between objects)",
       make_path_integrator, {/*local_scene*/ true, /*room_box*/ true, /*irradiance_mode*/ false, /*max_depth*/ true}},
  };
  return table;
}

const IntegratorEntry* find_integrator(const std::string& name) {
  for (const auto& e : integrator_registry())
    if (name == e.name) return &e;
  return nullptr;
}

bool is_integrator(const std::string& name) { return find_integrator(name) != nullptr; }

std::string unknown_integrator_message(const std::string& name) {
  std::string known;
  for (const auto& e : integrator_registry()) known += known.empty() ? e.name : std::string(", ") + e.name;
  return fmt::format("unknown integrator '{}' (known: {})", name, known);
}

std::unique_ptr<Integrator> make_integrator(const std::string& name, const RenderInputs& inputs) {
  if (const IntegratorEntry* e = find_integrator(name)) return e->create(inputs);
  throw InputError("", unknown_integrator_message(name));
}

}  // namespace insitu
