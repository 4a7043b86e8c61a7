// A texture of a material: linear texels sampled bilinearly and repeating, through the UV set and
// the affine map its file gives (glTF's texCoord and KHR_texture_transform).
//
// Coordinates. A mesh's UVs are stored in OBJ's convention, v = 0 at the bottom of the image
// (glTF's, v = 0 at the top, are turned at load: v_obj = 1 − v_gltf). A texture maps them to
// normalized image coordinates (s to the right, t down, one repeat per unit, texel centres at
// (i + ½)/W):
//   (s, t)ᵀ = A · (u, v, 1)ᵀ,   A = image_from_uv (2 × 3)
// For OBJ's map_Kd, A = [1 0 0; 0 −1 1]. For glTF, A = T · F with F(u, v) = (u, 1 − v) back to
// glTF's UVs and T = translation · rotation · scale of KHR_texture_transform (the extension's
// own order: its matrix is offset · rotation(−θ about the origin, as the spec writes it) · scale).
//
// An 8-bit colour texture keeps its sRGB-encoded values and is decoded after interpolation, as
// Cycles does with byte images (it stores them as bytes and converts the interpolated value):
// between a dark and a light texel the linear value is then below their linear mean, and the two
// renderers agree texel for texel (docs/validation.md, Materials).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/image.h"
#include "core/math.h"

namespace insitu {

// A texture's texels: an 8-bit file's bytes as stored (k/255: a quarter of the memory of floats,
// and decoded in about half the time: BM_DecodeTexture), or floats (16-bit and float files, and textures given
// as arrays). Exactly one of the two holds them.
struct Texels {
  ByteImage bytes;
  Image floats;

  Texels() = default;
  explicit Texels(Image f) : floats(std::move(f)) {}
  explicit Texels(ByteImage b) : bytes(std::move(b)) {}
  int width() const { return bytes.empty() ? floats.width : bytes.width; }
  int height() const { return bytes.empty() ? floats.height : bytes.height; }
  // Texel (x, y)'s first channel, and its first three (the first, repeated, for one channel).
  float value(int x, int y) const { return bytes.empty() ? *floats.at(x, y) : float(*bytes.at(x, y)) * kByte; }
  Rgb rgb(int x, int y) const {
    const int c = bytes.empty() ? floats.channels : bytes.channels;
    if (c < 3) return Rgb::Constant(value(x, y));
    if (!bytes.empty()) {
      const std::uint8_t* p = bytes.at(x, y);
      return Rgb(float(p[0]), float(p[1]), float(p[2])) * kByte;
    }
    return floats.rgb(x, y);
  }

 private:
  static constexpr float kByte = 1.0f / 255.0f;
};

// The UV sets at a surface point: glTF's TEXCOORD_0 and TEXCOORD_1 (OBJ has only the first).
using UvSets = std::array<Vec2f, 2>;

struct Texture {
  std::shared_ptr<const Texels> image;  // 3 channels, linear or (srgb) sRGB-encoded; null: no texture
  std::shared_ptr<const Texels> alpha;  // 1 channel, linear, the file's alpha; null: opaque
  std::string path;                     // the file it was read from (for exporters), or "" (embedded)
  int texcoord = 0;                     // which UV set
  bool srgb = false;                    // values sRGB-encoded: decoded after interpolation
  Eigen::Matrix<float, 2, 3> image_from_uv = obj_convention();

  explicit operator bool() const { return image != nullptr; }
  // Bilinear and repeating; a texture without an image is white. With an alpha channel, the colour
  // of what is there: Σ w a c / Σ w a over the four texels.
  Rgb sample(const UvSets& uv) const;
  // The alpha channel, bilinear and repeating as sample(); 1 without one.
  float sample_alpha(const UvSets& uv) const;

  static Eigen::Matrix<float, 2, 3> obj_convention() {
    Eigen::Matrix<float, 2, 3> a;
    a << 1, 0, 0, 0, -1, 1;
    return a;
  }
};

// A colour texture's image from its file (read_texture_file): an integer file keeps its sRGB-encoded
// values (srgb set), a float file is linear. Negative and non-finite values become 0.
void set_colour_image(Texture& t, ImageFile file);
// A data texture's image (roughness, metallic, a normal map): its stored values, k/255 for 8 bits,
// whatever the file's encoding. Negative and non-finite values become 0.
void set_data_image(Texture& t, ImageFile file);
// The texels of a file read by read_texture_file or read_texture_memory (its bytes, or its floats
// with negative and non-finite values 0), and of its alpha channel (null without one).
std::shared_ptr<const Texels> texels_of(ImageFile& file);
std::shared_ptr<const Texels> alpha_texels_of(ImageFile& file);

}  // namespace insitu
