// `insitu export-blender SCENE -o scene.py`: the whole insitu scene for Blender/Cycles,
// to compare with or to finish in Blender. Three files:
//   scene.py           the script: `blender --python scene.py` builds it in a new scene "insitu";
//                      `blender -b --python scene.py -- --render out.png [--samples N]` renders
//                      the composite over the photo
//   scene.meshes.bin   the objects' and mesh catchers' triangles as insitu loaded them (placed,
//                      polygons split, degenerate triangles dropped), in Blender's frame
//   scene.world.exr    the environment as insitu renders with it (shots merged, clipped light
//                      recovered), equirectangular in Blender's layout (light/equirect.h)
// and, where the photo determined the outside that the capture point saw as wall
// (RoomBox::unseen_outside), scene.outside.exr: the same with those directions given it, the
// world seen through the openings (the walls still emit scene.world.exr).
//
// What the script makes, each as insitu models it:
//   - the camera (interop/blender_camera.h), the photo as its background and, in the compositor,
//     under the render (Alpha Over);
//   - the environment as the world; with a room box, the box's walls emitting the environment
//     seen from the capture point (light/room_light.h) and catching shadows, with the openings
//     cut out so that the world's distant light comes through them; a wall lying on an infinite
//     local-scene plane is left out (the plane is that surface);
//   - the local scene as shadow catchers: infinite planes as squares 1000 times the scene's size,
//     meshes as loaded; their albedo the scene's, or the photo's mean (scene/catcher_albedo.h);
//   - the objects with insitu's BSDF (render/bsdf.h) as nodes; Cycles path traces them with the
//     scene's spp and, for the path integrator, its max_depth as the bounce limit.
// Approximate in Blender: the catchers' albedo is one colour (insitu uses the photo per pixel);
// the glossy lobe's Fresnel is at the normal, not the half-vector; Cycles' shadow catcher is not
// Debevec's differential rendering, though it renders the same shadows and bounce light.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "scene/pipeline.h"

namespace insitu {

struct BlenderExportPaths {
  std::string script, meshes, world, outside;
  std::string stem;  // scene.py -> scene
  // Where objects[i]'s glTF goes when Blender cannot read the original (Draco or meshopt
  // compression, which Blender 3.4's importer lacks): scene.objects<i>.glb.
  std::string gltf_copy(std::size_t i) const;
};
// scene.py -> scene.meshes.bin, scene.world.exr, scene.outside.exr (the extension .py replaced, or
// appended).
BlenderExportPaths blender_export_paths(const std::string& script_path);

struct BlenderExport {
  std::string script;
  std::string mesh_bytes;
  Image world;                                                   // equirectangular, Blender's layout
  Image outside;                                                 // the same, or empty (none written)
  std::vector<std::pair<std::string, std::string>> gltf_copies;  // path, .glb bytes
};
BlenderExport make_blender_export(const LoadedScene& scene, const BlenderExportPaths& paths);
// Writes the files, each atomically: the glTF copies, the world and the meshes first, the script last.
void write_blender_export(const BlenderExport& e, const BlenderExportPaths& paths);

// The room box's walls (insitu's frame, metres) as rectangles of four corners, counter-clockwise
// seen from inside: each wall cut along its openings' edges, the cells inside an opening dropped.
// A wall that lies on one of the infinite planes of `local_scene` is left out.
using Quad = std::array<Vec3d, 4>;
std::vector<Quad> room_wall_quads(const EnvironmentSpec::RoomBox& box, const std::vector<PlaneSpec>& local_scene);

extern const char* const kBlenderExportPrelude;  // the script's Python helpers: blender_prelude.py

}  // namespace insitu
