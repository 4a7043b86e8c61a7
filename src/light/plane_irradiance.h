// The room's irradiance over a plane of the local scene: the E in the photo-derived
// albedo ρ = π P / E of a real surface (path.cpp) must be what the room model delivers at that
// point. Outdoors (distant light) E depends only on the normal; in a room box with a sunlit window
// it changes across the floor — the capture point may see the sun that most of the floor does not,
// and E taken there makes the floor's ρ several times too small in the shade, its shadows too
// weak and the objects' view of it too dark.
//
// E(x) = ∫ L_room(x, ω) cos θ dω over the plane's upper hemisphere, without the objects, is
// estimated at the nodes of a grid over the plane's part inside the room box, by the path
// integrator's own estimator: a sample of the room's light (room_light.h) and a cosine-weighted
// sample, combined by the power heuristic:
//   Ê = 1/N Σ [ L(ω_l) cos θ_l / p_l · w_l + π L(ω_b) · w_b ]
// and read by bilinear interpolation. Nodes are 1/64 of the box's larger extent on the plane
// apart, N = 256: a few per cent of noise, and a sunlit patch's edge blurred over one cell.
// Other local-scene surfaces do not shade the plane here (its light from the room alone).
#pragma once
#include <atomic>
#include <vector>

#include "light/plane_grid.h"
#include "light/room_light.h"

namespace insitu {

class PlaneIrradiance {
 public:
  // `stop` (core/stop.h) is looked at before each row of nodes.
  PlaneIrradiance(const RoomLight& room, const RoomBox& box, const Vec3f& point, const Vec3f& normal, int cells = 64,
                  int samples = 256, const std::atomic<bool>* stop = nullptr);
  Rgb at(const Vec3f& x) const { return grid_.at(x); }  // bilinear; clamped to the grid
  // The estimator at one point, for the grid and the tests.
  static Rgb estimate(const RoomLight& room, const Vec3f& x, const Vec3f& normal, int samples, std::uint64_t key);

 private:
  PlaneGrid grid_;
};

}  // namespace insitu
