// The shots panel's stitched view: the cube as insitu assembles it from the six shots (their
// registered aims, gains and feathered blend: light/environment.h), unfolded as a cross seen from
// inside the room (light/preview.h), with each shot's outline in its own colour and the directions
// that no shot saw, which the assembly fills in from their neighbours, hatched.
#pragma once
#include <array>
#include <string>

#include "light/environment.h"
#include "light/sixshot.h"
#include "scene/spec.h"

namespace insitu {

// Shot s's frame as it was assembled: its axes as aimed, and half its field of view across and up
// as tangents (tan(hfov/2), tan(hfov/2) · height / width). `present`: the shot could be read.
struct ShotFrame {
  ShotBasis basis{Vec3d::UnitZ(), Vec3d::UnitY(), Vec3d::UnitX()};
  double tan_half_w = 0, tan_half_h = 0;
  bool present = false;
};

// The frames of the environment's six shots (their sizes as used, after any turn).
std::array<ShotFrame, 6> shot_frames(const EnvironmentSpec& env, const EnvironmentInfo& info);
// Whether the frame sees direction d (any length).
bool frame_sees(const ShotFrame& frame, const Vec3d& d);
// The share of the sphere's solid angle that no frame sees.
double gap_fraction(const std::array<ShotFrame, 6>& frames);

// Shot s's outline colour, as "#rrggbb": the picture's and the page's legend's.
const char* outline_colour(int s);

// The light of the scene's six shots as the render loads it: without a room box, anchored to the
// photo as calibrated (light/photo_anchor.h). `photo_note`: why the photo could not anchor them
// (no camera yet: too few points clicked, say), else empty.
CubeMap load_shots_as_rendered(const SceneSpec& spec, Warnings& warnings, EnvironmentInfo& info,
                               std::string& photo_note);

// The picture, an sRGB PNG: the cross at `face_px` pixels a face, outlines and hatched gaps.
std::string stitched_png(const std::string& scene_path, int face_px);

}  // namespace insitu
