// What glTF's extra lobes and cut-outs cost:
//   build/bench/insitu_bench --benchmark_filter='PrincipledSample|CutoutRays'
// BM_PrincipledSample: one sample() (with its eval and pdf) of the principled model, without and
// with a clear coat (Arg 0, 1), and as rough glass (Arg 2: transmission 1, roughness 0.3). BM_CutoutRays: 64 k rays
// through a 99 904-triangle sphere, opaque (0), MASK (1) and BLEND at alpha 0.5 (2): the price of Embree calling the
// alpha filter; as traced rays (Arg 1 = 0) and as shadow rays (1: EmbreeScene::transmittance, which through the
// BLEND sphere attenuates at both crossings).
#include <benchmark/benchmark.h>

#include "core/sampler.h"
#include "render/bsdf.h"
#include "render/embree_scene.h"
#include "../tests/uv_sphere.h"

namespace {
using namespace insitu;

void BM_PrincipledSample(benchmark::State& state) {
  PrincipledParams p;
  p.base = Rgb(0.6f, 0.4f, 0.2f);
  p.clearcoat = state.range(0) == 1 ? 1.0f : 0.0f;
  p.clearcoat_roughness = 0.05f;
  if (state.range(0) == 2) p.transmission = 1, p.roughness = 0.3f;
  const Bsdf b = Bsdf::principled(p);
  const Vec3f wo = Vec3f(0.5f, 0.1f, 0.8f).normalized();
  std::uint64_t k = 0;
  for (auto _ : state) {
    Sampler s(1, k++, 0);
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    benchmark::DoNotOptimize(b.sample(wo, ul, u1, u2, &bs));
    benchmark::DoNotOptimize(bs);
  }
}
BENCHMARK(BM_PrincipledSample)->Arg(0)->Arg(1)->Arg(2);

Mesh sphere_mesh(Material::AlphaMode mode) {
  const float centre[3] = {0, 0, 0};
  const test::UvSphere s = test::make_uv_sphere(224, 224, centre, 0.5f);
  Mesh m;
  for (std::size_t i = 0; i < s.pos.size(); i += 3) m.positions.emplace_back(s.pos[i], s.pos[i + 1], s.pos[i + 2]);
  for (std::size_t i = 0; i < s.uv.size(); i += 2) m.uvs.emplace_back(s.uv[i], s.uv[i + 1]);
  for (std::size_t i = 0; i < s.idx.size(); i += 3) {
    const std::array<std::uint32_t, 3> v = {s.idx[i], s.idx[i + 1], s.idx[i + 2]};
    const std::array<std::int32_t, 3> t = {std::int32_t(v[0]), std::int32_t(v[1]), std::int32_t(v[2])};
    m.triangles.push_back({v, {-1, -1, -1}, t, 0});
  }
  Material mat;
  mat.principled = true;
  mat.alpha_mode = mode;
  mat.alpha = 0.5f;
  mat.alpha_cutoff = 0.4f;
  m.materials.push_back(mat);
  return m;
}

// Arg 1: traced rays (intersect(), 0) or shadow rays (transmittance(), 1).
void BM_CutoutRays(benchmark::State& state) {
  const Material::AlphaMode modes[] = {Material::AlphaMode::kOpaque, Material::AlphaMode::kMask,
                                       Material::AlphaMode::kBlend};
  std::vector<Mesh> meshes;
  meshes.push_back(sphere_mesh(modes[state.range(0)]));
  const EmbreeScene scene(std::move(meshes));
  const bool shadow = state.range(1) == 1;
  constexpr int kRays = 1 << 16;
  double passed = 0;  // hits, or the transmittances' sum
  for (auto _ : state) {
    passed = 0;
    for (int k = 0; k < kRays; ++k) {
      Sampler s(2, std::uint64_t(k), 0);
      const Ray ray{Vec3f(s.next() - 0.5f, s.next() - 0.5f, 2.0f), Vec3f(0, 0, -1)};
      passed += shadow ? double(scene.transmittance(ray, 0.0f, 4.0f)) : double(scene.intersect(ray).valid());
    }
  }
  state.counters[shadow ? "mean_transmittance" : "hit_fraction"] = passed / kRays;
  state.SetItemsProcessed(state.iterations() * kRays);
}
BENCHMARK(BM_CutoutRays)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
