#include "scene/output_layers.h"

#include <cmath>
#include <limits>

#include "core/output_paths.h"
#include "core/text_file.h"
#include "output/composite.h"
#include "output/tonemap.h"
#include "render/checkpoint.h"

namespace insitu {

namespace {

Image finite(Image img) {
  constexpr float kMax = std::numeric_limits<float>::max();
  for (float& v : img.data)
    if (!std::isfinite(v)) v = std::isnan(v) ? 0.0f : std::copysign(kMax, v);
  return img;
}

// The objects' premultiplied RGB with their coverage as A.
Image rgba(const Image& rgb, const Image& alpha) {
  Image out(rgb.width, rgb.height, 4);
  for (std::size_t i = 0; i < std::size_t(rgb.width) * std::size_t(rgb.height); ++i) {
    for (std::size_t c = 0; c < 3; ++c) out.data[4 * i + c] = rgb.data[3 * i + c];
    out.data[4 * i + 3] = alpha.data[i];
  }
  return out;
}

// What the PNG or JPEG holds: the photo's own curve (photo), or another tone map; EXR and TIFF
// hold the linear composite.
Image display_image(const RenderResult& r, const OutputSpec& output) {
  if (is_linear_output(output.image)) return r.composite_linear;
  return output.tonemap.op == ToneMap::kPhoto ? r.composite_encoded : tonemap(r.composite_linear, output.tonemap);
}

}  // namespace

std::vector<OutputLayer> output_layers(const LoadedScene& scene, const RenderResult& r, const OutputSpec* output) {
  const std::vector<std::string> rgb = {"R", "G", "B"}, xyz = {"X", "Y", "Z"};
  const RenderLayers& l = r.layers;
  return {{"composite", rgb, finite(r.composite_linear)},
          {"objects", {"R", "G", "B", "A"}, finite(rgba(l.objects, l.alpha))},
          {"with", rgb, finite(l.with_objects)},
          {"without", rgb, finite(l.without_objects)},
          {"shadow_ratio", rgb, finite(shadow_ratio(l))},
          {"normal", xyz, finite(l.normal)},
          {"albedo", rgb, finite(l.albedo)},
          {"depth", {"Z"}, finite(l.depth)},
          {"samples", {"Y"}, l.samples},
          {"variance", {"Y"}, finite(l.variance)},
          {"photo", rgb, finite(scene.photo_linear)},
          {"display", rgb, finite(display_image(r, output ? *output : scene.spec.output)), false}};
}

std::vector<NamedPath> loaded_scene_inputs(const LoadedScene& scene) {
  std::vector<NamedPath> inputs = scene_input_files(scene.spec);
  for (const EmbreeScene* meshes : {scene.objects.get(), scene.catcher_meshes.get()})
    for (const Mesh& m : meshes->meshes())
      for (const auto& f : m.files) inputs.push_back({f, "read by " + m.source});
  return inputs;
}

void write_outputs(const LoadedScene& scene, const RenderResult& r, const OutputSpec* output,
                   const nlohmann::json& report_extra) {
  const OutputSpec& out = output ? *output : scene.spec.output;
  if (output) {
    SceneSpec spec = scene.spec;
    spec.output = out;
    check_outputs(loaded_scene_inputs(scene), scene_output_files(spec));
  }
  const std::vector<OutputLayer> layers = output_layers(scene, r, &out);
  if (!out.layers.empty()) {
    std::vector<ExrChannel> channels;
    for (const OutputLayer& layer : layers)
      if (layer.in_exr)
        for (std::size_t c = 0; c < layer.channels.size(); ++c) channels.push_back({layer.exr_channel(c), &layer.image, int(c)});
    write_exr_channels(out.layers, r.composite_linear.width, r.composite_linear.height, channels);
  }
  write_image(out.image, layers.back().image);
  nlohmann::json report = render_report(scene, r, &out);
  if (report_extra.is_object()) report.update(report_extra);
  write_text_file(report_path(out.image), report.dump(2) + "\n");
}

}  // namespace insitu
