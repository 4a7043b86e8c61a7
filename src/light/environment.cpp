#include "core/output_paths.h"
#include "light/environment.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>

#include "light/equirect.h"
#include "light/panorama.h"
#include "core/json_reader.h"
#include "light/sixshot.h"

namespace insitu {

Image linearize_photo(const ImageFile& photo, const EnvironmentInfo& info, std::size_t* clamped) {
  if (info.response && photo.bits == 8) {
    if (clamped) *clamped = 0;
    return linearize_with_response(photo, *info.response);
  }
  return linearize(photo, clamped);
}

namespace {

float median_luminance(std::vector<float> y) {
  if (y.empty()) return 0;
  std::nth_element(y.begin(), y.begin() + long(y.size() / 2), y.end());
  return y[y.size() / 2];
}

// The field of view of a shot: its own, the set's, EXIF's 35 mm-equivalent focal length (which
// describes the diagonal: 2·atan(43.27 mm / 2f)), or 90°.
// The field of view across the shot's width as used (after its rotation; read_shot_files has
// turned `file` already). A given hfov is across the width W0 as displayed (EXIF orientation
// applied, core/image.h), before rotate_deg; turned a quarter,
// the width is the stored height H0, and with the focal length f = W0 / (2 tan(hfov0/2)) in
// pixels, hfov = 2 atan(H0 / (2 f)) = 2 atan(tan(hfov0/2) · H0/W0).
double shot_hfov(const ShotSpec& shot, const EnvironmentSpec& spec, const ImageFile& file) {
  const std::optional<double> given = shot.hfov_deg ? shot.hfov_deg : spec.hfov_deg;
  if (given) {
    if (shot.rotate_deg % 180 == 0) return *given;
    const double h0_over_w0 = double(file.stored.width) / file.stored.height;
    return rad_to_deg(2 * std::atan(std::tan(0.5 * deg_to_rad(*given)) * h0_over_w0));
  }
  // The 35 mm equivalent focal length gives the diagonal field, which turning does not change.
  if (file.exposure.focal_35mm_mm) {
    const double w = file.stored.width, h = file.stored.height;
    const double tan_half_diag = 43.2666 / (2 * *file.exposure.focal_35mm_mm);
    return rad_to_deg(2 * std::atan(tan_half_diag * w / std::hypot(w, h)));
  }
  return 90.0;
}

// One shot's files (its brackets), each turned as the shot asks.
std::vector<ImageFile> read_shot_files(const EnvironmentSpec& spec, int f) {
  std::vector<ImageFile> files;
  for (const std::string& path : spec.shots[std::size_t(f)].files) {
    try {
      files.push_back(read_image_file(path));
      files.back().stored = rotated_clockwise(files.back().stored, spec.shots[std::size_t(f)].rotate_deg);
    } catch (const InputError& e) {
      throw e.with_context(spec.shots[std::size_t(f)].where);
    }
  }
  return files;
}

// Relative exposures of a bracket set: the given times, else EXIF.
std::vector<double> bracket_exposures(const ShotSpec& s, const std::vector<ImageFile>& files) {
  std::vector<double> k;
  for (std::size_t b = 0; b < files.size(); ++b) {
    if (!s.times_s.empty()) {
      k.push_back(s.times_s[b]);
      continue;
    }
    const auto rel = files[b].exposure.relative();
    if (!rel) throw InputError(s.where, fmt::format("{}: no exposure time in its EXIF; give \"times\"", s.files[b]));
    k.push_back(*rel);
  }
  return k;
}

// The camera response, from the first bracketed shot (hdr_merge.h), when there is one.
void recover_first_response(const EnvironmentSpec& spec, EnvironmentInfo& info) {
  for (int f = 0; f < 6 && !info.response; ++f)
    if (spec.shots[std::size_t(f)].files.size() >= 2) {
      const std::vector<ImageFile> files = read_shot_files(spec, f);
      try {
        info.response = recover_response(files, bracket_exposures(spec.shots[std::size_t(f)], files));
      } catch (const InputError& e) {
        throw e.with_context(spec.shots[std::size_t(f)].where);
      }
    }
}

// Each shot linear, in its own unit: merged brackets are already divided by k (k_shot = 1); a
// single shot carries its k when EXIF or "times" gives it.
struct LinearShots {
  ShotSet set;
  ShotSet clipped;  // clipped_mask of each shot (of the shortest bracket)
  std::array<std::optional<double>, 6> k_shot;
  bool all_singles_have_k = true;
};

// 1-channel image → 3 channels, each the same.
Image as_rgb(const Image& grey) {
  Image out(grey.width, grey.height, 3);
  for (std::size_t i = 0; i < grey.data.size(); ++i)
    out.data[3 * i] = out.data[3 * i + 1] = out.data[3 * i + 2] = grey.data[i];
  return out;
}

// One shot's linear radiance, from its brackets (`times`, their exposures) or its single file, and
// its k when known.
Image linear_shot(const ShotSpec& s, const std::vector<ImageFile>& fl, const std::vector<double>& times,
                  const ResponseCurve& response, int f, EnvironmentInfo& info, Warnings& warnings, LinearShots& out) {
  if (fl.size() >= 2) {
    out.k_shot[std::size_t(f)] = 1.0;
    return merge_brackets(fl, times, response);
  }
  std::size_t clamped = 0;
  Image linear = (fl.front().display_referred && fl.front().bits == 8) ? linearize_with_response(fl.front(), response)
                                                                       : linearize(fl.front(), &clamped);
  info.clamped_values += clamped;
  if (clamped > 0) warnings.add(s.files.front(), fmt::format("{} negative or non-finite values clamped to 0", clamped));
  const auto rel = s.times_s.empty() ? fl.front().exposure.relative() : std::optional<double>(s.times_s.front());
  if (rel)
    out.k_shot[std::size_t(f)] = *rel;
  else
    out.all_singles_have_k = false;
  return linear;
}

// Each shot is read, linearized and shrunk to the largest face the cube can have (shrunk_to_face)
// before the next is read, and its clipped mask made (1 channel) and shrunk after its radiance
// is: a 12-megapixel shot is 144 MB as float, and only one such image at a time is held beside
// the file's own pixels (the box filter treats channels apart, so the mask shrunk as one channel
// and then copied to three is the three-channel mask shrunk).
LinearShots linearize_shots(const EnvironmentSpec& spec, const ResponseCurve& response, EnvironmentInfo& info,
                            Warnings& warnings) {
  LinearShots out;
  out.set.faced_face = spec.faced_face;
  out.clipped.faced_face = spec.faced_face;
  const int max_face = spec.face_size > 0 ? spec.face_size : 1024;  // natural_face_size's cap
  for (int f = 0; f < 6; ++f) {
    const std::vector<ImageFile> fl = read_shot_files(spec, f);
    const ShotSpec& s = spec.shots[std::size_t(f)];
    const std::size_t k = std::size_t(f);
    out.set.names[k] = out.clipped.names[k] = s.files.front();
    const double hfov = out.set.hfov_deg[k] = out.clipped.hfov_deg[k] = info.hfov_deg[k] =
        shot_hfov(s, spec, fl.front());
    Image mask;
    try {
      const std::vector<double> times = fl.size() >= 2 ? bracket_exposures(s, fl) : std::vector<double>{};
      out.set.shots[k] = shrunk_to_face(linear_shot(s, fl, times, response, f, info, warnings, out), hfov, max_face);
      // The shortest bracket's clipped pixels: clipped in every bracket (merge_brackets).
      const std::size_t shortest =
          times.empty() ? 0 : std::size_t(std::min_element(times.begin(), times.end()) - times.begin());
      mask = clipped_mask(fl[shortest], 1);
    } catch (const InputError& e) {
      throw e.with_context(s.where);
    }
    info.clipped[k] = clipped_fraction(mask);
    if (info.clipped[k] > 0.001)
      warnings.add(s.files.front(), fmt::format("{:.1f}% of pixels clipped: radiance there is only a lower bound",
                                                100 * info.clipped[k]));
    out.clipped.shots[k] = as_rgb(shrunk_to_face(mask, hfov, max_face));
  }
  return out;
}

// Into the photo's unit by EXIF, value × k_photo / k_shot, when the photo and every single shot
// have it (returns true); the factor and exif modes are noted or checked here.
bool apply_exif_exposure(const EnvironmentSpec& spec, const ImageFile* photo, LinearShots& shots,
                         EnvironmentInfo& info) {
  const std::optional<double> k_photo = photo ? photo->exposure.relative() : std::nullopt;
  if (spec.exposure == EnvironmentSpec::Exposure::kFactor) {
    info.exposure_source = "factor";
    info.exposure_factor = spec.exposure_factor;
    return false;
  }
  if (k_photo && shots.all_singles_have_k) {
    info.exposure_source = "exif";
    for (int f = 0; f < 6; ++f)
      for (float& v : shots.set.shots[std::size_t(f)].data) v *= float(*k_photo / *shots.k_shot[std::size_t(f)]);
    return true;
  }
  if (spec.exposure == EnvironmentSpec::Exposure::kExif) {
    if (photo && !k_photo) throw InputError(spec.where + ".exposure", photo->path + ": no exposure time in its EXIF");
    for (int f = 0; f < 6; ++f)
      if (!shots.k_shot[std::size_t(f)])
        throw InputError(spec.where + ".exposure",
                         spec.shots[std::size_t(f)].files.front() + ": no exposure time in its EXIF");
  }
  return false;
}

// The smallest shot sets every face's size (natural_face_size). One far smaller than the others
// (a thumbnail, a 1×1 image among six photos) would shrink the whole environment without a word:
// it is said, naming the shot, when it halves (or worse) the faces the others would give.
void warn_if_one_shot_limits(const EnvironmentSpec& spec, const ShotSet& set, int n, Warnings& warnings) {
  int smallest = 0, others = 1024;
  for (int f = 1; f < 6; ++f)
    if (shot_face_size(set, f) < shot_face_size(set, smallest)) smallest = f;
  for (int f = 0; f < 6; ++f)
    if (f != smallest) others = std::min(others, shot_face_size(set, f));
  if (2 * n > others) return;
  warnings.add(
      spec.shots[std::size_t(smallest)].files.front(),
      fmt::format("{} × {} pixels: it limits every cube face to {} × {} texels (the other shots give {}); "
                  "give a larger shot, or environment.face_size",
                  set.shots[std::size_t(smallest)].width, set.shots[std::size_t(smallest)].height, n, n, others));
}

CubeMap assemble(const EnvironmentSpec& spec, const LinearShots& shots, EnvironmentInfo& info, Warnings& warnings) {
  const ShotSet& set = shots.set;
  const int n = spec.face_size > 0 ? spec.face_size : natural_face_size(set);
  if (spec.face_size <= 0) warn_if_one_shot_limits(spec, set, n, warnings);
  AssemblyInfo assembly;
  CubeMap cube;
  const bool any_clipped = *std::max_element(info.clipped.begin(), info.clipped.end()) > 0;
  CubeMap clipped_cube;
  try {
    cube = assemble_cube(set, n, &assembly, any_clipped ? &shots.clipped : nullptr, &clipped_cube);
  } catch (const InputError& e) {
    throw e.with_context(spec.where);
  }
  info.coverage = assembly.coverage;
  info.covered = std::move(assembly.covered);
  for (int f = 0; f < 6; ++f)
    if (assembly.coverage[std::size_t(f)] < 1.0)
      warnings.add(spec.shots[std::size_t(f)].files.front(),
                   fmt::format("face {1} is {0:.1f}% covered by the shots; the rest is filled from its neighbours",
                               100 * assembly.coverage[std::size_t(f)], face_name(f)));
  if (any_clipped) info.clipped_cube = std::move(clipped_cube);
  return cube;
}

// Without EXIF, the estimate: one factor that matches the medians of the photo and of the cube.
CubeMap scale_by_estimate(const CubeMap& cube, const ImageFile& photo, const EnvironmentSpec& spec,
                          EnvironmentInfo& info, Warnings& warnings) {
  const Image photo_linear = linearize_photo(photo, info);
  std::vector<float> yp, yc;
  for (int y = 0; y < photo_linear.height; ++y)
    for (int x = 0; x < photo_linear.width; ++x) yp.push_back(luminance(photo_linear.rgb(x, y)));
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < cube.size(); ++j)
      for (int i = 0; i < cube.size(); ++i) yc.push_back(luminance(cube.texel(f, i, j)));
  const float mp = median_luminance(yp), mc = median_luminance(yc);
  info.exposure_factor = (mp > 0 && mc > 0) ? double(mp / mc) : 1.0;
  info.exposure_source = "estimate";
  if (std::abs(info.exposure_factor - 1) > 0.02)
    warnings.add(spec.where, fmt::format("no EXIF exposure on the photo and {}: {} scaled by an estimated {:.3g} "
                                         "(median of the photo / median of the cube); give environment.exposure",
                                         spec.from_shots() ? "every shot" : "the panorama",
                                         spec.from_shots() ? "shots" : "the panorama", info.exposure_factor));
  return scaled(cube, Rgb::Constant(float(info.exposure_factor)));
}

// The image's placement in the sphere: a cube strip's faces, a whole 2:1 image, or a partial
// panorama placed by its GPano metadata (JPEG files only: where phones and 360° cameras write it).
std::optional<PanoramaPlacement> image_placement(const EnvironmentSpec& spec, const ImageFile& file) {
  const int w = file.stored.width, h = file.stored.height;
  if (file.format == "jpeg")
    if (auto gpano = read_gpano(spec.image, w, h)) return gpano;
  if (w == 2 * h) return whole_panorama(w, h);
  if (h == 6 * w) return std::nullopt;
  throw InputError(spec.where, fmt::format("{}: {}x{} is neither equirectangular (2:1, or partial with GPano "
                                           "metadata) nor a cube strip (1:6)",
                                           spec.image, w, h));
}

// A texel per pixel at the equator: a quarter of the full panorama's width, at most 1024 for an
// 8-bit panorama as for shots (sixshot.h natural_face_size).
CubeMap image_cube(const EnvironmentSpec& spec, const Image& img, const std::optional<PanoramaPlacement>& placement,
                   bool display_referred, double* coverage, std::vector<bool>* covered = nullptr) {
  if (!placement) {
    if (spec.face_size > 0 && spec.face_size != img.width)
      throw InputError(spec.where, fmt::format("{}: a cube strip has face size {}, face_size asks for {}", spec.image,
                                               img.width, spec.face_size));
    if (spec.yaw_deg != 0) throw InputError(spec.where + ".yaw_deg", spec.image + ": a cube strip cannot be turned");
    return cube_from_strip(img);
  }
  int n = std::max(1, int(std::lround(placement->full_width / 4)));
  if (display_referred) n = std::min(n, 1024);
  if (spec.face_size > 0) n = spec.face_size;
  return cube_from_panorama(img, *placement, spec.yaw_deg, n, coverage, 2, covered);
}

// The clip mask of the directions the panorama did not see is 0, as a shot's is where no shot
// covered (sixshot.h): its nearest edge, stretched there, is no measurement of clipped light.
void unclip_uncovered(CubeMap& clipped, const std::vector<bool>& covered) {
  const int n = clipped.size();
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (!covered[texel_index(f, i, j, n)]) clipped.set_texel(f, i, j, Rgb::Zero());
  clipped.update_borders();
}

// An 8-bit panorama into the photo's unit as a single shot: value × k_photo / k_pano by EXIF
// when both have it, else the estimate (scale_by_estimate).
CubeMap panorama_exposure(const EnvironmentSpec& spec, const ImageFile& file, const CubeMap& cube,
                          const ImageFile* photo, EnvironmentInfo& info, Warnings& warnings) {
  const std::optional<double> k_pano = file.exposure.relative();
  const std::optional<double> k_photo = photo ? photo->exposure.relative() : std::nullopt;
  if (k_pano && k_photo) {
    info.exposure_source = "exif";
    info.exposure_factor = *k_photo / *k_pano;
    return scaled(cube, Rgb::Constant(float(info.exposure_factor)));
  }
  if (spec.exposure == EnvironmentSpec::Exposure::kExif)
    throw InputError(spec.where + ".exposure", (!k_pano ? spec.image
                                                : photo ? photo->path
                                                        : std::string("the photo")) +
                                                   ": no exposure time in its EXIF");
  return photo ? scale_by_estimate(cube, *photo, spec, info, warnings) : cube;
}

// At most two images of the file's size at once (a 360° camera's 8K panorama is 350 MB as
// float): the stored pixels and the clipped mask, then the stored pixels and the linear ones.
CubeMap load_image_environment(const EnvironmentSpec& spec, Warnings& warnings, EnvironmentInfo& info,
                               const ImageFile* photo) {
  ImageFile file;
  std::optional<PanoramaPlacement> placement;
  try {
    file = read_image_file(spec.image);
    placement = image_placement(spec, file);
  } catch (const InputError& e) {
    throw e.with_context(spec.where);
  }
  info.panorama = file.display_referred;
  if (!info.panorama && spec.exposure == EnvironmentSpec::Exposure::kExif)
    throw InputError(spec.where + ".exposure", spec.image + ": an HDR image has no exposure to read: give a factor");
  if (info.panorama) {
    info.panorama_clipped = clipped_fraction(file);
    if (info.panorama_clipped > 0) info.clipped_cube = image_cube(spec, clipped_mask(file), placement, true, nullptr);
    if (info.panorama_clipped > 0.001)
      warnings.add(spec.image, fmt::format("{:.1f}% of pixels clipped: radiance there is only a lower bound",
                                           100 * info.panorama_clipped));
  }
  const int width = file.stored.width, height = file.stored.height;
  Image img = linearize(file, &info.clamped_values);
  file.stored = Image();
  CubeMap cube = image_cube(spec, img, placement, info.panorama, &info.panorama_coverage, &info.covered);
  img = Image();
  if (info.clipped_cube && !info.covered.empty()) unclip_uncovered(*info.clipped_cube, info.covered);
  if (info.clamped_values > 0)
    warnings.add(spec.image, fmt::format("{} negative or non-finite values clamped to 0", info.clamped_values));
  if (info.panorama && placement && info.panorama_coverage < 0.999)
    warnings.add(spec.image, fmt::format("the panorama saw {:.1f}% of the sphere ({}); the rest is its nearest "
                                         "edge, stretched (with a room box, the photo's view of the walls where it "
                                         "sees them: the report's environment.photo_fill)",
                                         100 * info.panorama_coverage, describe_view(*placement, width, height)));
  if (spec.exposure == EnvironmentSpec::Exposure::kFactor) {
    info.exposure_factor = spec.exposure_factor;
    info.exposure_source = "factor";
    return scaled(cube, Rgb::Constant(float(spec.exposure_factor)));
  }
  return info.panorama ? panorama_exposure(spec, file, cube, photo, info, warnings) : cube;
}

// Each shot's aim from the shots (shot_registration.h). A shot that could have been registered
// (its view overlaps a neighbour's) and was not is named with the reason; it keeps its nominal
// direction.
// Without a room box the light is distant, and the photo's calibrated camera anchors each group's
// common rotation (photo_anchor.h).
void anchor_to_the_photo(const EnvironmentSpec& spec, LinearShots& shots, Registration& r, const ImageFile& photo,
                         const Camera& camera, EnvironmentInfo& info, Warnings& warnings) {
  const PhotoAnchor anchor = anchor_to_photo(shots.set, r.group, linearize_photo(photo, info), camera);
  std::string loose;
  for (int f = 0; f < 6; ++f) {
    r.aim[std::size_t(f)] = anchor.correction[std::size_t(f)] * r.aim[std::size_t(f)];
    describe_aim(r.aim[std::size_t(f)], shot_basis(f, spec.faced_face), r.shots[std::size_t(f)]);
    if (!anchor.anchored[std::size_t(f)] && anchor.matches[std::size_t(f)] > 0)
      loose += (loose.empty() ? "" : ", ") + std::string(face_name(f));
  }
  if (!loose.empty())
    warnings.add(spec.where, "shots " + loose +
                                 ": their matches with the photo do not fix their aim; it is taken "
                                 "as registered");
  info.photo_anchor = anchor;
}

// "+x, up": the faces marked.
std::string shot_list(const std::array<bool, 6>& which) {
  std::string list;
  for (int f = 0; f < 6; ++f)
    if (which[std::size_t(f)]) list += (list.empty() ? "" : ", ") + std::string(face_name(f));
  return list;
}

// One warning for the shots the lines could not anchor, one for those a room box's axes would have
// turned past a hand's misaim (levelled by their plumb lines instead: room_lines.h, off_box).
void warn_of_the_lines(const EnvironmentSpec& spec, LineAxes axes, const LineAnchor& anchor, Warnings& warnings) {
  std::array<bool, 6> loose{}, off{};
  double off_deg = 0;
  for (std::size_t f = 0; f < 6; ++f) {
    loose[f] = !anchor.anchored[f] && !anchor.off_box[f];
    off[f] = anchor.off_box[f];
    off_deg = std::max(off_deg, anchor.off_box_turn_deg[f]);
  }
  if (const std::string list = shot_list(loose); !list.empty())
    warnings.add(spec.where, "shots " + list +
                                 (axes == LineAxes::room
                                      ? ": too few straight lines along two of the room's axes to check their aim; "
                                        "it is taken as given"
                                      : ": too few vertical lines to level them; their tilt is taken as registered"));
  if (const std::string list = shot_list(off); !list.empty())
    warnings.add(spec.where, fmt::format("shots {}: their lines run up to {:.1f}° off the room box's axes, more "
                                         "than a hand misaims ({:.0f}°): is the box drawn along the walls? They "
                                         "are levelled by their plumb lines only",
                                         list, off_deg, kMaxHandTurnDeg));
}

// The aims turned by the room's straight lines (room_lines.h): all three axes with a room box,
// the vertical edges alone (the shots levelled) without one.
void anchor_to_the_lines(const EnvironmentSpec& spec, LinearShots& shots, Registration& r, EnvironmentInfo& info,
                         Warnings& warnings) {
  const LineAxes axes = spec.room_box ? LineAxes::room : LineAxes::vertical;
  const LineAnchor anchor = anchor_to_room_axes(shots.set, r.group, axes);
  for (int f = 0; f < 6; ++f) {
    r.aim[std::size_t(f)] = anchor.correction[std::size_t(f)] * r.aim[std::size_t(f)];
    describe_aim(r.aim[std::size_t(f)], shot_basis(f, spec.faced_face), r.shots[std::size_t(f)]);
  }
  warn_of_the_lines(spec, axes, anchor, warnings);
  shots.set.aim = r.aim;
  info.line_anchor = anchor;
}

void register_aims(const EnvironmentSpec& spec, LinearShots& shots, EnvironmentInfo& info, Warnings& warnings,
                   const ImageFile* photo, const Camera* camera) {
  Registration r = register_shots(shots.set);
  shots.set.aim = r.aim;
  anchor_to_the_lines(spec, shots, r, info, warnings);
  if (!spec.room_box && photo && camera) anchor_to_the_photo(spec, shots, r, *photo, *camera, info, warnings);
  shots.set.aim = shots.clipped.aim = r.aim;
  info.registration = std::move(r);
}

// Each shot that overlaps a neighbour yet matched none: why, what aimed it instead, and whether
// its exposure and white balance were matched (shot_gains.h: only between shots whose aims are
// known, so not for a shot left at its nominal direction or only levelled).
void warn_of_unregistered(const EnvironmentSpec& spec, const EnvironmentInfo& info, const ShotGains& gains,
                          Warnings& warnings) {
  const Registration& r = *info.registration;
  for (std::size_t f = 0; f < 6; ++f) {
    const ShotAim& a = r.shots[f];
    if (!r.overlap || a.registered) continue;
    const LineAnchor* lines = info.line_anchor ? &*info.line_anchor : nullptr;
    const bool by_lines = lines && lines->anchored[f];
    std::string aim = "its nominal direction is used";
    if (by_lines && lines->axes == LineAxes::room && !lines->off_box[f])
      aim = "it is aimed by the room box's lines instead";
    else if (info.photo_anchor && info.photo_anchor->anchored[f])
      aim = "it is aimed by the photo instead";
    else if (by_lines)
      aim = "it is levelled by its plumb lines, its yaw nominal";
    const std::string matched =
        gains.pairs[f] > 0 ? "" : ", and its exposure and white balance are not matched to its neighbours'";
    warnings.add(spec.shots[f].files.front(), "not registered: " + a.reason + "; " + aim + matched);
  }
}

CubeMap load_shot_environment(const EnvironmentSpec& spec, Warnings& warnings, EnvironmentInfo& info,
                              const ImageFile* photo, const Camera* camera) {
  recover_first_response(spec, info);
  const ResponseCurve response = info.response.value_or(srgb_response());
  LinearShots shots = linearize_shots(spec, response, info, warnings);
  const bool per_shot_exif = apply_exif_exposure(spec, photo, shots, info);
  if (spec.register_shots == EnvironmentSpec::Register::kAuto)
    register_aims(spec, shots, info, warnings, photo, camera);
  const ShotPairs comparable = info.registration
                                   ? aimed_pairs(*info.registration, info.line_anchor ? &*info.line_anchor : nullptr,
                                                 info.photo_anchor ? &*info.photo_anchor : nullptr)
                                   : every_pair();  // "register": "none": the aims as given
  const ShotGains gains = overlap_gains(shots.set, &shots.clipped, comparable);
  apply_gains(shots.set, gains);
  info.shot_gain = gains.gain;
  if (info.registration) warn_of_unregistered(spec, info, gains, warnings);
  CubeMap cube = assemble(spec, shots, info, warnings);
  if (spec.exposure == EnvironmentSpec::Exposure::kFactor)
    return scaled(cube, Rgb::Constant(float(spec.exposure_factor)));
  if (!per_shot_exif && photo) return scale_by_estimate(cube, *photo, spec, info, warnings);
  return cube;
}

}  // namespace

CubeMap load_environment(const EnvironmentSpec& spec, Warnings& warnings, EnvironmentInfo* info_out,
                         const ImageFile* photo, const Camera* camera) {
  EnvironmentInfo info;
  CubeMap cube = spec.from_shots() ? load_shot_environment(spec, warnings, info, photo, camera)
                                   : load_image_environment(spec, warnings, info, photo);
  if (info_out) *info_out = info;
  return cube;
}

}  // namespace insitu
