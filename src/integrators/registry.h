// The integrators' registry: a plain table (no static-initialization tricks) mapping each name to
// a one-line summary, what it uses of the scene, a reader of its parameters and a factory.
//
// Parameters (pbrt-v4's ParameterDictionary + ReportUnused; Mitsuba's Properties). The keys of the
// scene's render object other than integrator, spp and seed are the integrators' parameters,
// given flat (render.max_depth, the form of DESIGN.md's sketch) or in the integrator's own object
// (render.path: {"max_depth": 5}), not both. Each integrator reads its own through
// IntegratorParams; resolve_integrator() then refuses a key that no integrator reads, and warns of
// one that only another integrator reads.
//
// Adding an integrator: one file in src/integrators/ (opening with the block that documents its
// parameters, then its reader and factory, then its row: `const IntegratorEntry& <name>_integrator()`)
// and its name in registry.cpp's list.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/json_reader.h"
#include "render/integrator.h"

namespace insitu {

// One integrator's view of the render object: find() looks in render.<integrator> when that is an
// object, else at render.<key>, and remembers every key asked for.
class IntegratorParams {
 public:
  IntegratorParams(const JsonBlock& render, const std::string& integrator);
  std::optional<JsonValue> find(const std::string& key);
  const std::set<std::string>& asked() const { return asked_; }
  // Whether the integrator has its own object, render.<integrator>; finish() then refuses the keys
  // in it that were not asked for.
  bool has_own_object() const { return own_ != nullptr; }
  void finish() const;

 private:
  const JsonBlock& render_;
  std::string integrator_;
  const json* own_ = nullptr;
  std::set<std::string> asked_;
};

// What an integrator uses of the scene beyond the objects and the cube: a setting it does not use
// has no effect, and the pipeline says so when the user gives it.
struct IntegratorCapabilities {
  bool local_scene = false;  // catches shadows on local_scene (differential rendering)
  bool room_box = false;     // uses environment.room_box
  bool monte_carlo = false;  // its noise falls as 1/√spp (insitu tradeoff renders it over a ladder);
                             // otherwise spp only anti-aliases
  // The roles `insitu tradeoff` gives (one integrator each): `reference` renders every light path
  // the others leave out, and makes the converged image the others are measured against and the
  // A/B's accurate side; `legacy` is the legacy real-time renderer kept exactly, the A/B's other.
  bool reference = false;
  bool legacy = false;
};

struct IntegratorEntry {
  const char* name;
  const char* summary;
  IntegratorCapabilities uses;
  // Reads and checks the parameters (InputError naming the key), returning them complete, with
  // defaults: the object the report prints and create() receives.
  json (*read_params)(IntegratorParams& params);
  std::unique_ptr<Integrator> (*create)(const RenderInputs& inputs, const json& params);
};

const std::vector<IntegratorEntry>& integrator_registry();
// The one entry whose capabilities have `reference` (`legacy`) set.
const IntegratorEntry& reference_integrator();
const IntegratorEntry& legacy_integrator();
// The entry named `name`, or nullptr.
const IntegratorEntry* find_integrator(const std::string& name);
// "unknown integrator 'x' (known: realtime, irradiance, path)".
std::string unknown_integrator_message(const std::string& name);

// The integrator `name` with its parameters read from the render object: refuses an unknown
// integrator (at render.integrator) and every key no integrator reads; warns of each key, or
// integrator's object, that only another integrator reads.
struct ResolvedIntegrator {
  const IntegratorEntry* entry = nullptr;
  json params;
};
ResolvedIntegrator resolve_integrator(const std::string& name, const JsonBlock& render, Warnings& warnings);

// The integrator `name` built with the parameters of a render object (default: none given), for
// tests and benchmarks that build their RenderInputs by hand. Throws InputError as above.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const RenderInputs& inputs,
                                            const json& render = json::object());

}  // namespace insitu
