// The room's light as the scene file describes it (DESIGN.md "Scene file"): an HDR image, or six
// shots with their brackets, field of view and exposure, and an optional room box. Plain data:
// the scene parser (scene/scene_file.h) fills it, load_environment (environment.h) reads it.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "light/cubemap.h"

namespace insitu {

// One shot: a single file, or exposure brackets (aligned, 8-bit) with their exposure times.
struct ShotSpec {
  std::vector<std::string> files;
  std::vector<double> times_s;     // empty: from EXIF
  std::optional<double> hfov_deg;  // across the width as displayed (EXIF orientation applied); empty: the set's, else
                                   // EXIF 35 mm focal length, else 90°
  int rotate_deg = 0;              // the files turned clockwise by 0, 90, 180 or 270 before use
  std::string key;                 // its key in the scene file ("+x", "front", "up", ...)
  std::string where;
};

struct EnvironmentSpec {
  std::string where;
  // An equirectangular image (2:1, or partial with GPano metadata: light/panorama.h) or a cube
  // strip (1:6): HDR, or 8-bit as a phone's panorama mode or a 360° camera gives it.
  std::string image;
  double yaw_deg = 0;             // the image turned about +Y: its centre column looks along +X turned by yaw
  std::array<ShotSpec, 6> shots;  // or six shots, by face (+X, −X, +Y, −Y, +Z, −Z)
  int faced_face = kNegZ;
  std::optional<double> hfov_deg;  // for every shot that does not give its own
  int face_size = 0;               // 0: natural size of the input
  // Optional parallax correction: the room as a box, and where the environment was captured.
  // Openings (windows, open doors): axis-aligned rectangles on the box's walls, through which the
  // light is distant (DESIGN.md "The room's light is not distant").
  struct Opening {
    Vec3d min = Vec3d::Zero(), max = Vec3d::Zero();  // equal on the wall's axis
    int axis = 0;                                    // the wall's: 0 x, 1 y, 2 z
  };
  struct RoomBox {
    Vec3d min = Vec3d::Zero(), max = Vec3d::Zero(), capture = Vec3d::Zero();
    std::vector<Opening> openings;
  };
  std::optional<RoomBox> room_box;
  // How shots are brought into the photo's radiance unit: auto (EXIF when the photo and every
  // single shot have it, else an estimate that is reported), exif (required), or a factor.
  enum class Exposure { kAuto, kExif, kFactor } exposure = Exposure::kAuto;
  double exposure_factor = 1.0;
  // Recover the strength of light that clipped in the shots against the photo (inverse_lighting.h).
  bool inverse_lighting = true;
  // Find where each shot really looked from the shots themselves (shot_registration.h), or take
  // the nominal directions as exact.
  enum class Register { kAuto, kNone } register_shots = Register::kAuto;
  // Balance the light's colour to the photo's (relight/photo_white_balance.h): shots and 8-bit
  // panoramas; an HDR image keeps its own.
  bool white_balance_to_photo = true;
  bool from_shots() const { return image.empty(); }
};

}  // namespace insitu
