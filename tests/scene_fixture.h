// A small valid scene in a temporary folder — a random 8-bit photo, a small equirectangular EXR
// environment and the quad from tests/data — that each test bends into the case it needs.
#pragma once
#include <nlohmann/json.hpp>
#include <random>

#include "core/image.h"
#include "test_util.h"

namespace insitu::test {

struct SceneFixture {
  TempDir dir;
  nlohmann::json scene;
  int width, height;

  explicit SceneFixture(int photo_width = 48, int photo_height = 32) : width(photo_width), height(photo_height) {
    std::mt19937 rng(5);
    Image photo(width, height, 3);
    for (float& v : photo.data) v = float(rng() % 256) / 255.0f;
    write_image(dir.file("photo.png"), photo);
    Image env(16, 8, 3);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 16; ++x) env.set_rgb(x, y, Rgb(1.0f, 0.8f, 0.6f) * (y < 4 ? 2.0f : 0.5f));
    write_image(dir.file("env.exr"), env);
    for (const char* f : {"good_quad.obj", "good_quad.mtl"})
      fs::copy_file(test_data(f), dir.path() / f, fs::copy_options::overwrite_existing);
    scene = {
        {"photo", "photo.png"},
        {"camera", {{"eye", {0.5, 2.0, 1.5}}, {"look", {0.5, 0.0, -0.5}}, {"hfov_deg", 60}}},
        {"environment", "env.exr"},
        {"objects", {{{"mesh", "good_quad.obj"}}}},
        {"render", {{"spp", 4}}},
    };
  }
  std::string write(const nlohmann::json& j) const { return dir.write("scene.json", j.dump(2)); }
  std::string write() const { return write(scene); }
};

}  // namespace insitu::test
