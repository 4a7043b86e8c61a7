#include "render_args.h"

#include <filesystem>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/output_paths.h"
#include "integrators/registry.h"
#include "output/tonemap.h"
#include "scene/pipeline.h"

namespace insitu {

SceneSpec render_spec(const RenderArgs& a) {
  SceneSpec spec = parse_scene_file(a.scene);
  if (!a.output.empty()) {
    const std::string ext = lower_extension(a.output);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
      throw InputError("-o " + a.output, "unsupported extension '" + ext + "' (use .png, .jpg, .exr, .tif)");
    spec.output.image = a.output;
    // A quick `-o test.png` must not overwrite the final render's layers and report.
    spec.output.layers = layers_path_for(a.output);
  }
  if (!a.layers.empty()) {
    if (a.layers == "none") {
      spec.output.layers.clear();
    } else {
      if (lower_extension(a.layers) != ".exr")
        throw InputError("--layers " + a.layers, "the layers are a multi-layer EXR: use .exr, or none");
      spec.output.layers = a.layers;
    }
  }
  if (a.spp > 0) spec.render.spp = a.spp;
  if (a.denoise) spec.denoise = true;
  if (a.seed >= 0) spec.render.seed = std::uint64_t(a.seed);
  if (a.noise_target >= 0) spec.render.noise_target = a.noise_target;
  if (!a.integrator.empty()) {
    if (!find_integrator(a.integrator)) throw InputError("--integrator", unknown_integrator_message(a.integrator));
    spec.render.integrator = a.integrator;
  }
  if (!a.irradiance.empty()) {
    spec.render.block.value["irradiance"] = a.irradiance;
  }
  if (!a.tonemap.empty()) {
    spec.output.tonemap.op = *parse_tonemap(a.tonemap);
    spec.given.insert("output.tonemap");
  }
  if (a.key > 0) {
    spec.output.tonemap.key = a.key;
    spec.given.insert("output.tonemap.key");
  }
  return spec;
}

nlohmann::json sum_args_json(const RenderArgs& a) {
  return {{"scene", std::filesystem::absolute(a.scene).lexically_normal().string()},
          {"spp", a.spp},
          {"seed", a.seed},
          {"integrator", a.integrator},
          {"irradiance", a.irradiance}};
}

PartRecord part_record_from_json(const std::string& text, const std::string& where) {
  PartRecord r;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    const nlohmann::json& a = j.at("args");
    r.args_text = json_text(a);
    r.args.scene = a.at("scene").get<std::string>();
    r.args.spp = a.at("spp").get<int>();
    r.args.seed = a.at("seed").get<long>();
    r.args.integrator = a.at("integrator").get<std::string>();
    r.args.irradiance = a.at("irradiance").get<std::string>();
    r.prepare_seconds = j.at("prepare_seconds").get<double>();
    r.render_seconds = j.at("render_seconds").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(where, "not a part of a split render (no record of its scene and settings)");
  }
  return r;
}

}  // namespace insitu
