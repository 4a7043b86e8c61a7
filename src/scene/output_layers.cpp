#include "scene/output_layers.h"

#include <cmath>
#include <limits>

#include "core/json_reader.h"
#include "core/output_paths.h"
#include "core/staged_writes.h"
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

// What the PNG or JPEG holds: the photo's own curve (photo), or another tone map, which shows
// where the photo clipped neutral; EXR and TIFF hold the linear composite.
Image display_image(const LoadedScene& scene, const RenderResult& r, const OutputSpec& output) {
  if (is_linear_output(output.image)) return r.composite_linear;
  if (output.tonemap.op == ToneMap::kPhoto) return r.composite_encoded;
  const Image clipped = clipped_photo_weight(r.layers, scene.photo);
  return tonemap(r.composite_linear, output.tonemap, &clipped);
}

}  // namespace

// Built in place: a braced list would copy every layer once more (31 float channels of the image:
// 340 MB at 1920 × 1440).
std::vector<OutputLayer> output_layers(const LoadedScene& scene, const RenderResult& r, const OutputSpec* output) {
  const std::vector<std::string> rgb = {"R", "G", "B"}, xyz = {"X", "Y", "Z"};
  const RenderLayers& l = r.layers;
  std::vector<OutputLayer> layers;
  layers.reserve(12);
  auto add = [&](const char* name, const std::vector<std::string>& channels, Image image, bool in_exr = true) {
    layers.push_back({name, channels, std::move(image), in_exr});
  };
  add("composite", rgb, finite(r.composite_linear));
  add("objects", {"R", "G", "B", "A"}, finite(rgba(l.objects, l.alpha)));
  add("with", rgb, finite(l.with_objects));
  add("without", rgb, finite(l.without_objects));
  add("shadow_ratio", rgb, finite(shadow_ratio(l)));
  add("normal", xyz, finite(l.normal));
  add("albedo", rgb, finite(l.albedo));
  add("depth", {"Z"}, finite(l.depth));
  add("samples", {"Y"}, l.samples);
  add("variance", {"Y"}, finite(l.variance));
  add("photo", rgb, finite(scene.photo_linear));
  add("display", rgb, finite(display_image(scene, r, output ? *output : scene.spec.output)), false);
  return layers;
}

std::vector<NamedPath> loaded_mesh_files(const LoadedScene& scene) {
  std::vector<NamedPath> files;
  for (const EmbreeScene* meshes : {scene.objects.get(), scene.catcher_meshes.get()})
    for (const Mesh& m : meshes->meshes())
      for (const auto& f : m.files) files.push_back({f, "read by " + m.source});
  return files;
}

std::vector<NamedPath> loaded_scene_inputs(const LoadedScene& scene) {
  std::vector<NamedPath> inputs = scene_input_files(scene.spec);
  for (NamedPath& f : loaded_mesh_files(scene)) inputs.push_back(std::move(f));
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
  // All or nothing: the layers, the image and the report are renamed together once all three are
  // written (a full disk while writing the report leaves the old image and layers, not new ones).
  StagedWrites stage;
  if (out.layers.empty()) {  // "layers": "none": only the display layer is made (a batch's stills)
    write_image(out.image, finite(display_image(scene, r, out)), nullptr, &stage);
  } else {
    const std::vector<OutputLayer> layers = output_layers(scene, r, &out);
    std::vector<ExrChannel> channels;
    for (const OutputLayer& layer : layers)
      if (layer.in_exr)
        for (std::size_t c = 0; c < layer.channels.size(); ++c)
          channels.push_back({layer.exr_channel(c), &layer.image, int(c)});
    write_exr_channels(out.layers, r.composite_linear.width, r.composite_linear.height, channels, false, &stage);
    write_image(out.image, layers.back().image, nullptr, &stage);
  }
  nlohmann::json report = render_report(scene, r, &out);
  if (report_extra.is_object()) report.update(report_extra);
  write_text_file(report_path(out.image), json_text(report, 2) + "\n", &stage);
  stage.commit();  // the report last: a batch counts an entry done by its report
}

}  // namespace insitu
