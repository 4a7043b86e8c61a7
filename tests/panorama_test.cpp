// A panorama as the room's light (light/panorama.h): where a partial one sits by its GPano XMP,
// how much of the sphere it saw (against the band's analytic solid angle), that its pixels land in
// the directions they saw, and its turn about +Y.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "core/colour.h"
#include "core/error.h"
#include "core/image.h"
#include "light/environment.h"
#include "light/equirect.h"
#include "light/panorama.h"
#include "light/texel_geometry.h"
#include "test_util.h"

namespace insitu {
namespace {

// A smooth colour of direction: each channel a different linear function, all positive.
Rgb pattern(const Vec3f& d) { return {1.0f + 0.5f * d.x(), 1.0f + 0.5f * d.y(), 1.0f + 0.3f * d.z() - 0.2f * d.x()}; }

// The full panorama of `pattern`, w × w/2, in light/equirect.h's layout.
Image full_pattern(int w) {
  Image img(w, w / 2, 3);
  for (int y = 0; y < w / 2; ++y)
    for (int x = 0; x < w; ++x)
      img.set_rgb(x, y, pattern(equirect_to_direction((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(w / 2))));
  return img;
}

Image crop(const Image& img, int left, int top, int w, int h) {
  Image out(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.set_rgb(x, y, img.rgb((left + x) % img.width, top + y));
  return out;
}

// A JPEG of `img` (sRGB-encoded) carrying `gpano` as XMP: an APP1 segment after the SOI marker,
// as phones write it (Adobe XMP specification part 3, 1.1.3).
void write_jpeg_with_xmp(const std::string& path, const Image& img, const std::string& gpano_attributes) {
  Image encoded = img;
  for (float& v : encoded.data) v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));
  write_image(path, encoded);
  std::ifstream in(path, std::ios::binary);
  const std::string jpeg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string xmp =
      "<?xpacket begin=\"\" id=\"W5M0MpCehiHzreSzNTczkc9d\"?><x:xmpmeta xmlns:x=\"adobe:ns:meta/\">"
      "<rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"><rdf:Description rdf:about=\"\" "
      "xmlns:GPano=\"http://ns.google.com/photos/1.0/panorama/\" " +
      gpano_attributes + "/></rdf:RDF></x:xmpmeta><?xpacket end=\"w\"?>";
  const std::string payload = std::string("http://ns.adobe.com/xap/1.0/") + '\0' + xmp;
  const std::size_t length = payload.size() + 2;
  std::string segment = {char(0xFF), char(0xE1), char(length >> 8), char(length & 0xFF)};
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << jpeg.substr(0, 2) << segment << payload << jpeg.substr(2);
}

std::string gpano(int full_w, int full_h, int crop_w, int crop_h, int left, int top,
                  const std::string& projection = "equirectangular") {
  return "GPano:ProjectionType=\"" + projection + "\" GPano:FullPanoWidthPixels=\"" + std::to_string(full_w) +
         "\" GPano:FullPanoHeightPixels=\"" + std::to_string(full_h) + "\" GPano:CroppedAreaImageWidthPixels=\"" +
         std::to_string(crop_w) + "\" GPano:CroppedAreaImageHeightPixels=\"" + std::to_string(crop_h) +
         "\" GPano:CroppedAreaLeftPixels=\"" + std::to_string(left) + "\" GPano:CroppedAreaTopPixels=\"" +
         std::to_string(top) + "\"";
}

TEST(Panorama, GPanoPlacesAPartialPanoramaAndFollowsAResize) {
  test::TempDir dir;
  const std::string path = dir.file("pano.jpg");
  // Written by the camera as 1024 × 256 of a 2048 × 1024 panorama; resized to 512 × 128 since.
  write_jpeg_with_xmp(path, Image(512, 128, 3, 0.5f), gpano(2048, 1024, 1024, 256, 512, 384));
  const auto p = read_gpano(path, 512, 128);
  ASSERT_TRUE(p.has_value());
  EXPECT_DOUBLE_EQ(p->full_width, 1024);
  EXPECT_DOUBLE_EQ(p->full_height, 512);
  EXPECT_DOUBLE_EQ(p->left, 256);
  EXPECT_DOUBLE_EQ(p->top, 192);
  // A JPEG without GPano has no placement.
  write_image(dir.file("plain.jpg"), Image(64, 32, 3, 0.5f));
  EXPECT_FALSE(read_gpano(dir.file("plain.jpg"), 64, 32).has_value());
}

// GPano that cannot place this image is refused, naming the file and what is wrong.
TEST(Panorama, GPanoThatCannotPlaceTheImageIsRefused) {
  test::TempDir dir;
  const std::string path = dir.file("bad.jpg");
  auto error_of = [&](const std::string& attributes, int w = 128, int h = 64) {
    write_jpeg_with_xmp(path, Image(w, h, 3, 0.5f), attributes);
    try {
      read_gpano(path, w, h);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of(gpano(256, 128, 128, 64, 0, 0, "cylindrical")).find("ProjectionType"), std::string::npos);
  EXPECT_NE(error_of(gpano(256, 100, 128, 64, 0, 0)).find("2:1"), std::string::npos);
  EXPECT_NE(error_of(gpano(256, 128, 128, 64, 0, 100)).find("outside"), std::string::npos);
  EXPECT_NE(error_of(gpano(256, 128, 128, 32, 0, 0)).find("shape"), std::string::npos);
  EXPECT_NE(error_of("GPano:FullPanoWidthPixels=\"256\"").find("CroppedAreaImageWidthPixels"), std::string::npos);
  EXPECT_NE(error_of(gpano(256, 128, 128, 64, 0, 0) + " GPano:Dummy=\"1\"").find("no error"), std::string::npos);
}

// A crop of half the azimuth between polar angles θ0 and θ1 saw ½ · (cos θ0 − cos θ1)/2 of the
// sphere; across the seam (u from 0.75 to 1.25) the same.
TEST(Panorama, CoverageIsTheBandsSolidAngle) {
  const Image img(128, 64, 3, 1.0f);
  const double expected = 0.5 * (std::cos(kPi / 4) - std::cos(3 * kPi / 4)) / 2;  // θ 45°..135°
  for (int left : {64, 192}) {
    double coverage = 0;
    cube_from_panorama(img, PanoramaPlacement{256, 128, double(left), 32}, 0.0, 48, &coverage, 4);
    EXPECT_NEAR(coverage, expected, 0.01) << "left " << left;
  }
  double whole = 0;
  cube_from_panorama(Image(256, 128, 3, 1.0f), whole_panorama(256, 128), 0.0, 16, &whole);
  EXPECT_NEAR(whole, 1.0, 1e-9);
}

// The band between polar angles 45° and 135° over all azimuths: a texel whose centre lies within
// it by more than half a texel's diagonal (at most 4.5° at a 16 face) is covered, one outside it
// by as much is not; the covered texels' solid angle is the band's, to within a texel ring; a whole
// panorama leaves the mask empty, as the assembly does for shots that cover every face.
TEST(Panorama, TheTexelsTheCropDidNotSeeAreUncovered) {
  constexpr int n = 16;
  std::vector<bool> covered;
  cube_from_panorama(Image(256, 64, 3, 1.0f), PanoramaPlacement{256, 128, 0, 32}, 0.0, n, nullptr, 2, &covered);
  ASSERT_EQ(covered.size(), std::size_t(6 * n * n));
  const std::vector<double> omega = face_solid_angles(n);
  double covered_sr = 0;
  int checked_in = 0, checked_out = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double elevation_deg = rad_to_deg(std::asin(double(texel_direction(f, i, j, n).normalized().y())));
        const bool in = covered[std::size_t((f * n + j) * n + i)];
        covered_sr += in ? omega[std::size_t(j * n + i)] : 0.0;
        if (std::abs(elevation_deg) < 40.5) {
          EXPECT_TRUE(in) << f << " " << i << " " << j;
          ++checked_in;
        }
        if (std::abs(elevation_deg) > 49.5) {
          EXPECT_FALSE(in) << f << " " << i << " " << j;
          ++checked_out;
        }
      }
  EXPECT_GT(checked_in, 400);
  EXPECT_GT(checked_out, 250);
  EXPECT_NEAR(covered_sr / (4 * kPi), std::cos(kPi / 4), 0.06);
  cube_from_panorama(Image(256, 128, 3, 1.0f), whole_panorama(256, 128), 0.0, n, nullptr, 2, &covered);
  EXPECT_TRUE(covered.empty());
}

// A band of a panorama, read at its own level into a cube of 16 a face.
EnvironmentSpec band_spec(const std::string& path) {
  EnvironmentSpec spec;
  spec.image = path;
  spec.exposure = EnvironmentSpec::Exposure::kFactor;
  spec.exposure_factor = 1;
  spec.face_size = 16;
  return spec;
}

// A partial JPEG whose top row is white (clipped) and the rest grey, read as the room's light: the
// band's edge is clipped where the crop saw it, and the texels it did not see (the stretched white
// above the band) are not clipped, as a shot's uncovered texels are not (sixshot.h).
TEST(Panorama, WhatTheCropDidNotSeeIsNotClipped) {
  test::TempDir dir;
  Image band(256, 64, 3, 0.2f);
  for (int x = 0; x < band.width; ++x) band.set_rgb(x, 0, Rgb::Ones());
  write_jpeg_with_xmp(dir.file("band.jpg"), band, gpano(256, 128, 256, 64, 0, 32));
  const EnvironmentSpec spec = band_spec(dir.file("band.jpg"));
  Warnings warnings;
  EnvironmentInfo info;
  const CubeMap cube = load_environment(spec, warnings, &info);
  ASSERT_TRUE(info.clipped_cube.has_value());
  ASSERT_EQ(info.covered.size(), std::size_t(6 * 16 * 16));
  int clipped_seen = 0, uncovered = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        const float clip = info.clipped_cube->texel(f, i, j).maxCoeff();
        if (info.covered[texel_index(f, i, j, 16)]) {
          clipped_seen += clip > 0;
          continue;
        }
        ++uncovered;
        EXPECT_EQ(clip, 0.0f) << f << " " << i << " " << j;
      }
  EXPECT_GT(clipped_seen, 0);
  EXPECT_GT(uncovered, 200);
  EXPECT_GT(cube.lookup_nearest(Vec3f(0, 1, 0)).minCoeff(), 0.9f);  // the white edge, stretched
}

// The warning of a partial panorama says what it saw and which lights it cannot hold: a band of
// rows 32 … 96 of a full 128 spans elevations 90° − 180° · 96/128 = −45° to 90° − 180° · 32/128 = 45°.
TEST(Panorama, APartialPanoramasWarningSaysWhatItDidNotSee) {
  EXPECT_EQ(describe_view(PanoramaPlacement{256, 128, 0, 32}, 256, 64),
            "elevations -45° to 45°, 360° around: a light above 45° (a ceiling lamp) or below -45° is not in it");
  // Without the bottom 45° (a tripod), 180° of azimuth: rows 0 … 96 of 128, 128 of 256 columns.
  EXPECT_EQ(describe_view(PanoramaPlacement{256, 128, 64, 0}, 128, 96),
            "elevations -45° to 90°, 180° around: a light below -45° or outside its 180° of azimuth is not in it");
  EXPECT_EQ(describe_view(whole_panorama(256, 128), 256, 128), "elevations -90° to 90°, 360° around");
  test::TempDir dir;
  write_jpeg_with_xmp(dir.file("band.jpg"), Image(256, 64, 3, 0.2f), gpano(256, 128, 256, 64, 0, 32));
  const EnvironmentSpec spec = band_spec(dir.file("band.jpg"));
  Warnings warnings;
  load_environment(spec, warnings);
  ASSERT_EQ(warnings.items.size(), 1u);
  EXPECT_NE(warnings.items[0].find("saw 70."), std::string::npos) << warnings.items[0];
  EXPECT_NE(warnings.items[0].find("a light above 45° (a ceiling lamp)"), std::string::npos) << warnings.items[0];
}

// Texels whose directions the crop saw (a texel inside it, away from its edge) carry what the
// full panorama carries there, across the seam too; the rest carry a colour of the crop's edge.
TEST(Panorama, ACropsPixelsLandWhereTheFullPanoramaHasThem) {
  const Image full = full_pattern(512);
  const CubeMap truth = cube_from_panorama(full, whole_panorama(512, 256), 0.0, 32);
  for (int left : {128, 448}) {
    const Image part = crop(full, left, 64, 192, 128);
    const CubeMap cube = cube_from_panorama(part, PanoramaPlacement{512, 256, double(left), 64}, 0.0, 32);
    int inside = 0;
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i) {
          const Vec2f uv = direction_to_equirect(texel_direction(f, i, j, 32));
          const float x = std::fmod(uv.x() * 512 - float(left) + 512, 512.0f), y = uv.y() * 256 - 64;
          if (x < 4 || x > 188 || y < 4 || y > 124) continue;  // two texels from the crop's edge
          ++inside;
          EXPECT_LT((cube.texel(f, i, j) - truth.texel(f, i, j)).cwiseAbs().maxCoeff(), 1e-3f)
              << "left " << left << " face " << f << " texel " << i << "," << j;
        }
    EXPECT_GT(inside, 6 * 32 * 32 / 8) << "left " << left;
  }
}

// Turned by yaw about +Y: what the panorama's own frame sees along R_y(−yaw)·d lands at d. At 90°
// its centre column (+X) looks along −Z.
TEST(Panorama, YawTurnsThePanoramaAboutUp) {
  const Image full = full_pattern(256);
  const CubeMap plain = cube_from_panorama(full, whole_panorama(256, 128), 0.0, 24);
  for (double yaw : {90.0, -35.0}) {
    const CubeMap turned = cube_from_panorama(full, whole_panorama(256, 128), yaw, 24);
    const float c = float(std::cos(deg_to_rad(yaw))), s = float(std::sin(deg_to_rad(yaw)));
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < 24; j += 3)
        for (int i = 0; i < 24; i += 3) {
          const Vec3f d = texel_direction(f, i, j, 24);
          const Vec3f d_pano(c * d.x() - s * d.z(), d.y(), s * d.x() + c * d.z());  // R_y(−yaw) d
          EXPECT_LT((turned.texel(f, i, j) - plain.lookup(d_pano)).cwiseAbs().maxCoeff(), 0.02f) << "yaw " << yaw;
        }
    if (yaw == 90.0) {
      EXPECT_LT((turned.lookup(Vec3f(0, 0, -1)) - pattern(Vec3f(1, 0, 0))).cwiseAbs().maxCoeff(), 0.01f);
    }
  }
}

}  // namespace
}  // namespace insitu
