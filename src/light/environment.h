// The room's light as a radiance cube in the photo's radiance unit (DESIGN.md "Colour and
// light"), from six shots (single images or exposure brackets) or from an image: HDR, or an 8-bit
// panorama (equirectangular 2:1 or partial, light/panorama.h; or a vertical strip of the six
// faces 1:6).
//
// Shots are linearized by the inverse sRGB curve, or by the camera response recovered from the
// first bracketed shot (hdr_merge.h), which then also linearizes the photo. They are brought into
// the photo's unit by their relative exposure k = t·ISO/N²: value × k_photo / k_shot (a merged
// bracket set is already divided by k). Without EXIF on the photo and every single shot, `auto`
// estimates one factor, median(photo luminance) / median(cube luminance), and says so. An 8-bit
// panorama is one single shot: the sRGB curve, its clipped pixels, EXIF or the estimate. An HDR
// image keeps its own unit unless a factor is given.
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "light/cubemap.h"
#include "core/error.h"
#include "light/hdr_merge.h"
#include "light/environment_spec.h"
#include "light/photo_anchor.h"
#include "light/room_lines.h"
#include "light/shot_gains.h"
#include "light/shot_registration.h"

namespace insitu {

struct EnvironmentInfo {
  std::size_t clamped_values = 0;                       // negative or non-finite inputs set to 0
  std::array<double, 6> coverage = {1, 1, 1, 1, 1, 1};  // per face, from six shots
  // Per texel, where a face is covered less than fully: whether a shot (AssemblyInfo) or the
  // panorama (cube_from_panorama) saw it; else empty.
  std::vector<bool> covered;
  std::array<double, 6> clipped = {0, 0, 0, 0, 0, 0};         // fraction of clipped pixels per shot
  std::array<double, 6> hfov_deg = {90, 90, 90, 90, 90, 90};  // per shot, as used (after turning)
  std::optional<ResponseCurve> response;                      // recovered from brackets
  double exposure_factor = 1;                                 // applied to shots without EXIF
  std::string exposure_source = "none";                       // "exif", "factor", "estimate", "none"
  // With clipped shots: per texel of the cube, the fraction of it that was clipped (the shots'
  // masks assembled like the shots themselves; a merged bracket's clipping is its shortest's).
  std::optional<CubeMap> clipped_cube;
  std::optional<Registration> registration;  // six shots with "register": "auto"
  std::optional<LineAnchor> line_anchor;     // ... its lines: a room box's axes, or plumb edges
  std::optional<PhotoAnchor> photo_anchor;   // ... without one, given the photo's camera: to the photo
  // An image that is display-referred (8- or 16-bit: a panorama): linearized by the sRGB curve, its
  // clipped pixels in clipped_cube, brought into the photo's unit as a single shot is.
  bool panorama = false;
  double panorama_coverage = 1;  // the fraction of the sphere the image saw (light/panorama.h)
  double panorama_clipped = 0;   // the fraction of its pixels that clipped
  std::array<Rgb, 6> shot_gain = {Rgb::Ones(), Rgb::Ones(), Rgb::Ones(),
                                  Rgb::Ones(), Rgb::Ones(), Rgb::Ones()};  // from overlaps (shot_gains.h)
};

// `photo` (as stored) gives k_photo and the estimate; without it shots keep their own unit.
// `camera`, the photo's, anchors registered shots to the photo where no room box does
// (photo_anchor.h).
CubeMap load_environment(const EnvironmentSpec& spec, Warnings& warnings, EnvironmentInfo* info = nullptr,
                         const ImageFile* photo = nullptr, const Camera* camera = nullptr);

// The photo in linear units: through the recovered response when there is one, else sRGB-decoded.
Image linearize_photo(const ImageFile& photo, const EnvironmentInfo& info, std::size_t* clamped = nullptr);

}  // namespace insitu
