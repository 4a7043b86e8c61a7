// insitu export-blender SCENE -o scene.py [--spp N]
//
// The whole scene for Blender/Cycles (interop/blender_export.h): scene.py, scene.meshes.bin,
// scene.world.exr, and scene.outside.exr in a room box whose unseen outside the photo determined.
// `blender --python scene.py` builds it; `blender -b --python scene.py -- --render out.png` renders
// the composite over the photo.
#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "core/output_paths.h"
#include "interop/blender_export.h"
#include "render/gltf_mesh.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"

namespace insitu {
namespace {

struct ExportArgs {
  std::string scene, output;
  int spp = 0;
};

int run_export_blender(const ExportArgs& a) {
  if (lower_extension(a.output) != ".py") throw InputError("-o " + a.output, "the export is a Python script: use .py");
  SceneSpec spec = parse_scene_file(a.scene);
  spec.output = {};  // this verb writes no render: the scene's outputs are neither checked nor made
  for (auto it = spec.given.begin(); it != spec.given.end();)
    it = it->rfind("output.", 0) == 0 ? spec.given.erase(it) : std::next(it);
  if (a.spp > 0) spec.render.spp = a.spp;
  const BlenderExportPaths paths = blender_export_paths(a.output);
  std::vector<NamedPath> outputs = {{paths.script, "-o"},
                                    {paths.meshes, "the meshes"},
                                    {paths.world, "the world"},
                                    {paths.outside, "the world outside the openings"}};  // written only with a room box
  for (std::size_t i = 0; i < spec.objects.size(); ++i)  // written only for a compressed glTF
    if (is_gltf_path(spec.objects[i].mesh)) outputs.push_back({paths.gltf_copy(i), "a decompressed copy"});
  std::vector<NamedPath> inputs = scene_input_files(spec);
  inputs.push_back({a.scene, "the scene file"});
  check_outputs(inputs, outputs);  // before any work
  const LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  for (const EmbreeScene* meshes : {scene.objects.get(), scene.catcher_meshes.get()})
    for (const Mesh& m : meshes->meshes()) {  // the MTL files and textures they named
      std::vector<NamedPath> files;
      for (const auto& f : m.files) files.push_back({f, "read by " + m.source});
      check_outputs(files, outputs);
    }
  const BlenderExport e = make_blender_export(scene, paths);
  write_blender_export(e, paths);
  for (const auto& copy : e.gltf_copies) std::printf("%s\n", copy.first.c_str());
  for (const auto& p : {paths.script, paths.meshes, paths.world}) std::printf("%s\n", p.c_str());
  if (e.outside.width > 0) std::printf("%s\n", paths.outside.c_str());
  return 0;
}

}  // namespace

Command add_export_blender_command(CLI::App& app) {
  auto a = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export-blender", "write the scene as a Blender script (camera, objects, room, shadow catchers, world)");
  cmd->add_option("scene", a->scene, "the scene file (JSON)")->required();
  cmd->add_option("-o,--output", a->output,
                  "the script (.py); SCRIPT_STEM.meshes.bin and SCRIPT_STEM.world.exr (and, with a room box, "
                  "SCRIPT_STEM.outside.exr) are written beside it")
      ->required();
  cmd->add_option("--spp", a->spp, "Cycles samples per pixel [default: the scene's render.spp]")
      ->check(CLI::Range(1, kMaxSpp));
  return [cmd, a] { return cmd->parsed() ? run_export_blender(*a) : -1; };
}

}  // namespace insitu
