#include "integrators/registry.h"

#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <stdexcept>

namespace insitu {

// Each integrator's file declares its own row: name, summary, capabilities, reader and factory
// (Mitsuba's plugin registration, but asked for by name here rather than registered by a static
// initializer, so no order of initialization matters).
const IntegratorEntry& realtime_integrator();
const IntegratorEntry& irradiance_integrator();
const IntegratorEntry& path_integrator();

const std::vector<IntegratorEntry>& integrator_registry() {
  static const std::vector<IntegratorEntry> table = {realtime_integrator(), irradiance_integrator(), path_integrator()};
  return table;
}

namespace {
const IntegratorEntry& the_one(bool IntegratorCapabilities::*role, const char* what) {
  const IntegratorEntry* found = nullptr;
  for (const auto& e : integrator_registry())
    if (e.uses.*role) {
      if (found) throw std::logic_error(std::string("two integrators are the ") + what);
      found = &e;
    }
  if (!found) throw std::logic_error(std::string("no integrator is the ") + what);
  return *found;
}
}  // namespace

const IntegratorEntry& reference_integrator() { return the_one(&IntegratorCapabilities::reference, "reference"); }
const IntegratorEntry& legacy_integrator() { return the_one(&IntegratorCapabilities::legacy, "legacy"); }

const IntegratorEntry* find_integrator(const std::string& name) {
  for (const auto& e : integrator_registry())
    if (name == e.name) return &e;
  return nullptr;
}

std::string unknown_integrator_message(const std::string& name) {
  std::string known;
  for (const auto& e : integrator_registry()) known += known.empty() ? e.name : std::string(", ") + e.name;
  return fmt::format("unknown integrator '{}' (known: {})", name, known);
}

IntegratorParams::IntegratorParams(const JsonBlock& render, const std::string& integrator)
    : render_(render), integrator_(integrator) {
  const auto it = render.value.find(integrator);
  if (it != render.value.end() && it->is_object()) own_ = &*it;
}

std::optional<JsonValue> IntegratorParams::find(const std::string& key) {
  asked_.insert(key);
  const auto flat = render_.value.find(key);
  const bool has_flat = flat != render_.value.end() && &*flat != own_;
  if (own_ && own_->contains(key)) {
    if (has_flat)
      throw InputError(render_.file + ":" + render_.path + "." + key,
                       fmt::format("given twice: here and in render.{} (give it once)", integrator_));
    return JsonValue(own_->at(key), render_.file, render_.path + "." + integrator_ + "." + key);
  }
  if (!has_flat) return std::nullopt;
  return JsonValue(*flat, render_.file, render_.path + "." + key);
}

void IntegratorParams::finish() const {
  if (!own_) return;
  for (auto it = own_->begin(); it != own_->end(); ++it)
    if (!asked_.count(it.key())) {
      std::string known;
      for (const auto& k : asked_) known += (known.empty() ? "" : ", ") + k;
      throw InputError(
          render_.file + ":" + render_.path + "." + integrator_ + "." + it.key(),
          fmt::format("unknown key (the {} integrator reads: {})", integrator_, known.empty() ? "nothing" : known));
    }
}

namespace {

constexpr const char* kLoopKeys[] = {"integrator", "spp", "seed", "noise_target"};

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// Every key of the render object, checked against what the integrators asked for.
void check_render_keys(const std::string& name, const JsonBlock& render,
                       const std::map<std::string, std::vector<std::string>>& readers, Warnings& warnings) {
  for (auto it = render.value.begin(); it != render.value.end(); ++it) {
    const std::string& key = it.key();
    if (std::find(std::begin(kLoopKeys), std::end(kLoopKeys), key) != std::end(kLoopKeys)) continue;
    if (find_integrator(key) && it->is_object()) {
      if (key != name) warnings.add("render." + key, fmt::format("has no effect: the {} integrator is used", name));
      continue;
    }
    const auto rd = readers.find(key);
    if (rd == readers.end()) {
      // A value for the render, or an integrator's own object of parameters: "irradiance" is both
      // (the irradiance mode, and the irradiance integrator's object), said once in each role.
      std::vector<std::string> known(std::begin(kLoopKeys), std::end(kLoopKeys)), blocks;
      for (const auto& [k, who] : readers) known.push_back(k);
      for (const auto& e : integrator_registry()) blocks.push_back(e.name);
      throw InputError(render.file + ":" + render.path + "." + key,
                       "unknown key (expected one of: " + join(known) +
                           "; or an integrator's object of parameters: " + join(blocks) + ")");
    }
    if (std::find(rd->second.begin(), rd->second.end(), name) == rd->second.end())
      warnings.add("render." + key, fmt::format("has no effect: the {} integrator does not read it (only {} {})", name,
                                                join(rd->second), rd->second.size() == 1 ? "does" : "do"));
  }
}

}  // namespace

ResolvedIntegrator resolve_integrator(const std::string& name, const JsonBlock& render, Warnings& warnings) {
  ResolvedIntegrator r;
  r.entry = find_integrator(name);
  if (!r.entry) throw InputError(render.file + ":" + render.path + ".integrator", unknown_integrator_message(name));
  // Every integrator reads the render object, so that a key is known if any of them reads it and a
  // bad value is refused whichever integrator is chosen.
  std::map<std::string, std::vector<std::string>> readers;
  for (const auto& e : integrator_registry()) {
    IntegratorParams params(render, e.name);
    json read = e.read_params(params);
    params.finish();
    if (&e == r.entry) r.params = std::move(read);
    for (const auto& key : params.asked()) readers[key].push_back(e.name);
  }
  check_render_keys(name, render, readers, warnings);
  return r;
}

std::unique_ptr<Integrator> make_integrator(const std::string& name, const RenderInputs& inputs, const json& render) {
  Warnings ignored;
  const ResolvedIntegrator r = resolve_integrator(name, {render, "", "$.render"}, ignored);
  return r.entry->create(inputs, r.params);
}

}  // namespace insitu
