// The room's light white-balanced to the photo. The photo is the colour reference: the objects
// are composited into it, so the light that shades them must have its colour. Shots from a phone
// on auto white balance carry the balance of the shots (the median shot's, after shot_gains.h),
// which may not be the photo's.
//
// The photo and the room's light see the same room. A photo pixel on the room's walls, floor or
// ceiling should show the radiance the light predicts there: RoomLight::radiance(eye, ray), the
// box's wall seen from the photo's camera as the capture point saw it, or the cube along the ray
// without a box. On a Lambertian surface the two differ by the balance alone. Per photo pixel p
// (a grid of at most kWhiteBalancePixels, unclipped in the photo and in the light, not dark, not
// through an opening), the chromatic offset of each channel c is
//   o_c = log(P_c / L_c) − log(Y(P) / Y(L)),
// its luminance part removed (that is exposure: environment.h sets it). The gain is
//   w_c = exp(median_p o_c), scaled so that Y(w) = 1,
// so a grey light keeps its luminance, and its σ is the median's, 1.2533 · 1.4826 · MAD / √n. It
// is determined by at least kWhiteBalanceMinPixels pixels. The median keeps what is not the room
// (a sofa already there, a glossy highlight) from moving it. The light is compared at a face of
// at most 64 texels: a balance is a property of the whole light, not of its detail.
#pragma once
#include <optional>
#include <string>

#include "core/camera.h"
#include "core/image.h"
#include "light/cubemap.h"
#include "light/room_light.h"

namespace insitu {

constexpr int kWhiteBalancePixels = 4000;
constexpr int kWhiteBalanceMinPixels = 100;

struct WhiteBalance {
  Rgb gain = Rgb::Ones();   // to multiply the light by (Y(gain) = 1)
  Rgb sigma = Rgb::Zero();  // of each channel's log gain
  int pixels = 0;           // photo pixels compared
  bool determined = false;
  std::string reason;  // when not determined: why
};

// `clipped`: the light's clipped cube (environment.h), or null; `photo_clipped`: the photo's
// clipped mask (hdr_merge.h).
WhiteBalance white_balance_to_photo(const CubeMap& radiance, const CubeMap* clipped, const std::optional<RoomBox>& box,
                                    const Camera& camera, const Image& photo_linear, const Image& photo_clipped);

}  // namespace insitu
