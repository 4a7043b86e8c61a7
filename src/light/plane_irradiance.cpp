#include "light/plane_irradiance.h"

#include <algorithm>
#include <cmath>

#include "core/sampler.h"
#include "core/sampling.h"

namespace insitu {

Rgb PlaneIrradiance::estimate(const RoomLight& room, const Vec3f& x, const Vec3f& n, int samples, std::uint64_t key) {
  Rgb sum = Rgb::Zero();
  for (int k = 0; k < samples; ++k) {
    Sampler s(0x1AAD1A4CEull, key, std::uint64_t(k));
    const float ue = s.next(), us = s.next(), ut = s.next();
    const RoomSample rs = room.sample(x, ue, us, ut);
    const float cos_l = n.dot(rs.dir);
    if (rs.pdf > 0 && cos_l > 0) sum += rs.radiance * (cos_l / rs.pdf * power_heuristic(rs.pdf, cos_l / kPiF));
    const Vec3f wi = cosine_sample(n, s.next(), s.next());
    const float pdf_b = n.dot(wi) / kPiF;
    if (pdf_b > 0) {
      const RoomLookup l = room.lookup(x, wi);
      sum += kPiF * l.radiance * power_heuristic(pdf_b, l.pdf);
    }
  }
  return sum / float(std::max(1, samples));
}

PlaneIrradiance::PlaneIrradiance(const RoomLight& room, const RoomBox& box, const Vec3f& point, const Vec3f& normal,
                                 int cells, int samples, const std::atomic<bool>* stop)
    : grid_(box, point, normal, cells) {
  const Vec3f n = grid_.normal();
  grid_.fill([&](const Vec3f& x, std::uint64_t key) { return estimate(room, x, n, samples, key); }, stop);
}

}  // namespace insitu
