// The light sources that clipped in the shots: the texels of the cube whose clipped
// fraction (EnvironmentInfo::clipped_cube) is at least ½, grouped into regions connected across
// face edges (4-neighbourhood, or within a reach: find_clipped_sources). Each region is one source
// whose radiance is known only from below: the clipped value L0 is a lower bound, and the true
// radiance is L0 · s with s ≥ 1 unknown.
#pragma once
#include <array>
#include <vector>

#include "light/cubemap.h"

namespace insitu {

struct ClippedSource {
  std::vector<std::array<int, 3>> texels;  // (face, i, j)
  Vec3f dir_world = Vec3f::Zero();         // the luminance-weighted mean direction, unit
  double solid_angle_sr = 0;
  double power = 0;  // Σ Y(L0) ΔΩ: its share of c's irradiance-like power
};

// The source made of these texels (face, i, j) of `radiance`: its direction, solid angle and power.
ClippedSource clipped_source(std::vector<std::array<int, 3>> texels, const CubeMap& radiance);

// Largest power (at the lower bound) first. Every region is its own source, up to `max_sources`;
// only beyond that are the rest merged into the last one kept (a bound on the fit's unknowns for a
// cube of many specks). The lower bound does not rank the true power: a lamp clips in fewer texels
// than a window's edge, and is brighter by ×100 where the edge is by ×1.5. With four sources the
// two ceiling lamps of docs/validation.md (15 texels each) were merged with the windows' edges and
// eight specks into one scale, which the fit could only leave at 1 (the raised grey ball's
// objects 1.5× too bright). Regions the photo cannot tell stay at the lower bound (inverse_lighting.h).
// `reach_texels` > 0 joins regions of one face whose gap in i or j is at most 2⌈reach/2⌉ texels
// (each dilated by ⌈reach/2⌉): one source, whose parts (split_into_parts) the fit still tells
// apart where the photo can. The dilation stops at a face's edge (the fill crosses it between
// texels either side that it reached). 0 joins 4-neighbours.
constexpr int kMaxClippedSources = 32;
std::vector<ClippedSource> find_clipped_sources(const CubeMap& clipped, const CubeMap& radiance,
                                                int max_sources = kMaxClippedSources, int reach_texels = 0);

// A source cut into parts of at most block × block texels of a face: a clipped window holds the
// sky and the sun, whose true radiances differ by orders of magnitude, so one scale cannot
// describe it; the parts' scales are fitted each, and judged together (inverse_lighting.h).
std::vector<ClippedSource> split_into_parts(const ClippedSource& source, const CubeMap& radiance, int block);

// The cube with only the given source's texels (all else black), and the cube with every source's
// texels multiplied by its scale.
CubeMap source_only(const CubeMap& radiance, const ClippedSource& source);
CubeMap with_scaled_sources(const CubeMap& radiance, const std::vector<ClippedSource>& sources,
                            const std::vector<double>& scales);
// The same with a factor per channel.
CubeMap with_scaled_sources_rgb(const CubeMap& radiance, const std::vector<ClippedSource>& sources,
                                const std::vector<Rgb>& scales);

// Σ Y(L) ΔΩ over the whole cube (the denominator of ClippedSource::power's share).
double cube_power(const CubeMap& radiance);

}  // namespace insitu
