// The surface model of the objects: Lambertian diffuse plus a glossy GGX microfacet lobe.
//
//   f(ωo, ωi) = (1 − F(ωo·n))·ρ_d/π  +  D(h) G(ωo, ωi) F(ωi·h) / (4 |ωo·n| |ωi·n|)
//
// ρ_d = Kd × map_Kd; the specular reflectance at normal incidence F0 = Ks (Schlick's Fresnel,
// F = F0 + (1 − F0)(1 − cos)^5); roughness α = √(2/(Ns + 2)), Walter et al. 2007's match of a
// Phong exponent to a microfacet width. D is GGX (Trowbridge–Reitz), G Smith's separable
// shadowing-masking. The diffuse term is weighted by what the specular Fresnel reflection leaves,
// so the total never reflects more than arrives (checked by BsdfTest.EnergyIsConserved).
// With Ks = 0 the model is exactly Lambertian.
//
// Sampling: the glossy lobe with probability p_s = max(F(ωo·n)) when Ks > 0 (half-vectors from
// D(h)·cos θ_h, so pdf(ωi) = D cos θ_h / (4 |ωo·h|)), else cosine-weighted; pdf() is the mixture.
// Directions are in a local frame with the normal along +z.
#pragma once
#include "core/math.h"
#include "core/sampling.h"

namespace insitu {

struct Material;

struct BsdfSample {
  Vec3f wi;    // local
  Rgb weight;  // f·cos θ_i / pdf
  float pdf = 0;
};

class Bsdf {
 public:
  Bsdf(const Rgb& diffuse, const Rgb& f0, float alpha);
  static Bsdf from_material(const Material& m, const Rgb& base_colour);

  Rgb eval(const Vec3f& wo, const Vec3f& wi) const;   // f, local directions, both above
  float pdf(const Vec3f& wo, const Vec3f& wi) const;  // solid-angle density of sample()
  bool sample(const Vec3f& wo, float u_lobe, float u1, float u2, BsdfSample* out) const;
  bool glossy() const { return glossy_; }

 private:
  float specular_probability(float cos_o) const;
  Rgb diffuse_, f0_;
  float alpha_;
  bool glossy_;
};

}  // namespace insitu
