// A camera from fSpy (https://fspy.io), which matches vanishing lines and so works where no 3D
// point is known: the JSON that fSpy exports ("File > Export > Camera parameters").
//
// fSpy's conventions, read from its source (stuffmatic/fSpy src/gui/solver/solver.ts and
// coordinates-util.ts) and its Blender importer (stuffmatic/fSpy-Blender fspy_blender/addon.py):
//   - image plane: the longer side of the image spans [−1, 1], y up; principalPoint is there, so
//       u_px = W/2 + x·L/2,  v_px = H/2 − y·L/2,  L = max(W, H);
//   - relativeFocalLength f_rel in the same units: fx = fy = f_rel·L/2; horizontalFieldOfView
//     (radians) is 2·atan(1/f_rel) for wide and tall images alike, i.e. across the longer side;
//   - cameraTransform.rows: the 4×4 camera-to-world matrix, the camera looking down its −z with
//     +y up (OpenGL, Blender), in fSpy's world, which its Blender importer uses as Blender's:
//     Z up. insitu's world is Y up (DESIGN.md), so p_insitu = (x, z, −y) of fSpy's (x, y, z), as
//     Blender's OBJ exporter converts; and camera axes (x, −y, −z) to OpenCV's.
//   - fSpy's units are taken as metres (set fSpy's reference distance in metres).
// The photo may be a resized copy of fSpy's image: only the aspect ratio must agree (to 1 %).
#pragma once
#include <string>

#include "core/camera.h"
#include "core/error.h"

namespace insitu {

// Throws InputError naming the file and the JSON path for a missing or malformed field, a
// transform that is not a rotation and a translation, or an image of another aspect ratio.
Camera camera_from_fspy(const std::string& path, int width, int height, Warnings* warnings = nullptr);

}  // namespace insitu
