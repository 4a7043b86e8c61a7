// A panorama as the room's light: an equirectangular image from a phone's panorama mode or a 360°
// camera, whole or partial, turned about the world's up axis.
//
// A partial panorama (a phone's sweep covers about 360° × 90°) says where it sits in the full
// sphere by Google's Photo Sphere XMP metadata (GPano, developers.google.com/streetview/spherical-
// metadata): the full panorama's size FullPanoWidthPixels × FullPanoHeightPixels, and the cropped
// image's CroppedAreaImageWidthPixels × CroppedAreaImageHeightPixels at CroppedAreaLeftPixels,
// CroppedAreaTopPixels. Those are in the pixels of the image as the camera wrote it; an image
// resized since keeps its metadata, so they are scaled by image width / CroppedAreaImageWidthPixels.
//
// The full panorama is equirectangular in light/equirect.h's convention, turned by yaw_deg about
// +Y (right-handed: 90° turns the centre column from +X to −Z). A direction the cropped image did
// not see takes the nearest pixel it did see (its edge, stretched), as a shot's uncovered texels
// are filled from their neighbours; `coverage` says how much of the sphere was seen.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "light/cubemap.h"

namespace insitu {

struct PanoramaPlacement {
  double full_width = 0, full_height = 0;  // the full panorama, in the image's pixels
  double left = 0, top = 0;                // where the image's top-left corner sits in it
  bool partial(int width, int height) const {
    return left != 0 || top != 0 || full_width != width || full_height != height;
  }
};

// What an image of `width` × `height` so placed saw, for a warning: its elevations and how far
// around, with the lights it cannot hold ("elevations -45° to 45°, 360° around: a light above 45°
// (a ceiling lamp) or below -45° is not in it"). Row y of the full panorama is at elevation
// 90° − 180° y / full_height (light/equirect.h: v = acos(d.y)/π).
std::string describe_view(const PanoramaPlacement& placement, int width, int height);

// The placement from the file's GPano XMP metadata (read with Exiv2), for an image of
// `width` × `height`; nullopt when the file has none. Metadata that cannot describe an
// equirectangular panorama holding this image (another projection, a full size that is not 2:1,
// a crop outside it) is an InputError naming the file and the field.
std::optional<PanoramaPlacement> read_gpano(const std::string& path, int width, int height);

// A whole 2:1 image: the placement that covers the sphere.
PanoramaPlacement whole_panorama(int width, int height);

// The cube of `face_size` seen through the panorama, averaging ss × ss bilinear samples per
// texel; `coverage` (optional): the fraction of the sphere's solid angle the image saw;
// `covered` (optional): per texel, indexed (face·n + j)·n + i, whether the image saw any of its
// samples, as AssemblyInfo::covered is for shots (left empty where it saw every texel).
CubeMap cube_from_panorama(const Image& img, const PanoramaPlacement& placement, double yaw_deg, int face_size,
                           double* coverage = nullptr, int ss = 2, std::vector<bool>* covered = nullptr);

}  // namespace insitu
