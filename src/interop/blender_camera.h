// The camera as a Blender Python script: `insitu calibrate ... --blender cam.py`, then
// `blender --python cam.py` (or Text Editor > Run Script) creates it in the open scene.
//
// Blender's camera from insitu's pinhole (DESIGN.md: OpenCV axes, Y-up world, pixels):
//   - render resolution W × H, pixel aspect a_x / a_y = fy/fx (one of them 1; model f+c+a);
//     Blender measures in aspect-corrected units, W·a_x by H·a_y, and with sensor fit AUTO its
//     36 mm sensor lies along the longer, L = max(W·a_x, H·a_y): lens_mm = fx·a_x · 36 / L;
//   - lens shift in units of L (for square pixels as fSpy's importer sets it):
//     shift_x = (W/2 − cx)·a_x / L, shift_y = (cy − H/2)·a_y / L;
//   - pose: camera-to-world in Blender's Z-up world, camera looking down −z with +y up:
//       matrix_world = [B R_cvᵀ diag(1, −1, −1) | B eye],  B: (x, y, z) ↦ (x, −z, y);
//   - the photo, when given, as the camera's background image.
#pragma once
#include <string>

#include "core/camera.h"

namespace insitu {

// insitu's Y-up world to Blender's Z-up world: B: (x, y, z) ↦ (x, −z, y). The one place it is written.
Mat3d blender_from_insitu();
inline Vec3d to_blender(const Vec3d& p) { return blender_from_insitu() * p; }
// The camera's matrix_world in Blender (and fSpy's cameraTransform): [B R_cvᵀ diag(1, −1, −1) | B eye].
Mat4d blender_camera_to_world(const Camera& camera);

std::string blender_camera_script(const Camera& camera, const std::string& photo_path = "");
// The script's body alone, for a larger script (interop/blender_export.h) that has imported bpy and
// mathutils.Matrix and bound `scene`: sets the render size and creates the camera as scene.camera.
std::string blender_camera_lines(const Camera& camera, const std::string& photo_path = "");

}  // namespace insitu
