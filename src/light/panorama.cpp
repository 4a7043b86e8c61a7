#include "light/panorama.h"

#include <exiv2/exiv2.hpp>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "light/equirect.h"
#include "light/texel_geometry.h"

namespace insitu {

namespace {

// Exiv2's XMP toolkit is initialised once, before any thread parses (Exiv2::XmpParser docs), and
// its messages are muted: a bad file is this function's InputError, not a line on stderr.
void init_exiv2() {
  static std::once_flag once;
  std::call_once(once, [] {
    Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute);
    Exiv2::XmpParser::initialize();
  });
}

struct GPanoFields {
  std::string path;
  const Exiv2::XmpData& xmp;
  bool has(const char* name) const { return xmp.findKey(Exiv2::XmpKey(std::string("Xmp.GPano.") + name)) != xmp.end(); }
  double number(const char* name) const {
    const auto it = xmp.findKey(Exiv2::XmpKey(std::string("Xmp.GPano.") + name));
    if (it == xmp.end()) throw InputError(path, fmt::format("GPano metadata without {}", name));
    const std::string text = it->toString();
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || !std::isfinite(v) || v < 0 || v > 1e6)
      throw InputError(path, fmt::format("GPano:{} is \"{}\", not a pixel count", name, text));
    return v;
  }
};

PanoramaPlacement placement_from(const GPanoFields& g, int width, int height) {
  if (g.has("ProjectionType")) {
    const std::string type = g.xmp.findKey(Exiv2::XmpKey("Xmp.GPano.ProjectionType"))->toString();
    if (type != "equirectangular")
      throw InputError(g.path, fmt::format("GPano:ProjectionType is \"{}\": only equirectangular panoramas", type));
  }
  const double crop_w = g.number("CroppedAreaImageWidthPixels"), crop_h = g.number("CroppedAreaImageHeightPixels");
  if (!(crop_w > 0) || !(crop_h > 0)) throw InputError(g.path, "GPano metadata with an empty cropped area");
  // The metadata is in the pixels the camera wrote; the image may have been resized since.
  const double s = width / crop_w;
  if (std::abs(height / crop_h - s) > 0.01 * s)
    throw InputError(g.path, fmt::format("{} x {} pixels, but GPano's cropped area is {} x {}: not the same shape",
                                         width, height, crop_w, crop_h));
  PanoramaPlacement p{s * g.number("FullPanoWidthPixels"), s * g.number("FullPanoHeightPixels"),
                      s * g.number("CroppedAreaLeftPixels"), s * g.number("CroppedAreaTopPixels")};
  if (std::abs(p.full_width - 2 * p.full_height) > 0.01 * p.full_width)
    throw InputError(g.path, fmt::format("GPano's full panorama is {} x {}: an equirectangular one is 2:1",
                                         p.full_width / s, p.full_height / s));
  if (p.left >= p.full_width || p.top + height > p.full_height + 0.5 || width > p.full_width + 0.5)
    throw InputError(g.path, "GPano's cropped area lies outside its full panorama");
  return p;
}

// Right-handed turn about +Y by `rad`: (x, y, z) -> (x cos + z sin, y, −x sin + z cos).
Vec3f turned_about_y(const Vec3f& d, float c, float s) {
  return {c * d.x() + s * d.z(), d.y(), -s * d.x() + c * d.z()};
}

// Where a direction of the panorama's own frame falls in the image, in pixels (x across, y down,
// pixel centres at +0.5), and whether the image saw it. Outside the crop: its nearest edge; across
// the seam the nearer way round.
struct ImagePoint {
  float x, y;
  bool seen;
};

ImagePoint image_point(const Vec3f& d_pano, const PanoramaPlacement& p, int width, int height) {
  const Vec2f uv = direction_to_equirect(d_pano);
  double x = uv.x() * p.full_width - p.left, y = uv.y() * p.full_height - p.top;
  x = std::fmod(x + 2 * p.full_width, p.full_width);  // in [0, full_width)
  bool seen = y >= 0 && y < height && x < width;
  if (x >= width) x = (x - width < p.full_width - x) ? width : 0.0;  // nearest edge, round the seam
  y = std::clamp(y, 0.0, double(height));
  return {float(x), float(y), seen};
}

// Bilinear at pixel coordinates; x wraps when the image spans the full width, else clamps.
Rgb bilinear_wrapped(const Image& img, float x, float y, bool wrap_x) {
  x -= 0.5f, y -= 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float wx = x - float(x0), wy = y - float(y0);
  auto col = [&](int xi) {
    return wrap_x ? ((xi % img.width) + img.width) % img.width : std::clamp(xi, 0, img.width - 1);
  };
  auto row = [&](int yi) { return std::clamp(yi, 0, img.height - 1); };
  const Rgb a = img.rgb(col(x0), row(y0)), b = img.rgb(col(x0 + 1), row(y0));
  const Rgb c = img.rgb(col(x0), row(y0 + 1)), d = img.rgb(col(x0 + 1), row(y0 + 1));
  return (1 - wy) * ((1 - wx) * a + wx * b) + wy * ((1 - wx) * c + wx * d);
}

}  // namespace

PanoramaPlacement whole_panorama(int width, int height) { return {double(width), double(height), 0, 0}; }

std::string describe_view(const PanoramaPlacement& placement, int width, int height) {
  const double high_deg = 90 - 180 * placement.top / placement.full_height;
  const double low_deg = 90 - 180 * (placement.top + height) / placement.full_height;
  const double around_deg = std::min(360.0, 360 * width / placement.full_width);
  std::string out = fmt::format("elevations {:.0f}° to {:.0f}°, {:.0f}° around", low_deg, high_deg, around_deg);
  std::vector<std::string> missed;
  if (high_deg < 89.5) missed.push_back(fmt::format("above {:.0f}° (a ceiling lamp)", high_deg));
  if (low_deg > -89.5) missed.push_back(fmt::format("below {:.0f}°", low_deg));
  if (around_deg < 359.5) missed.push_back(fmt::format("outside its {:.0f}° of azimuth", around_deg));
  if (missed.empty()) return out;
  out += ": a light " + missed.front();
  for (std::size_t k = 1; k < missed.size(); ++k) out += (k + 1 == missed.size() ? " or " : ", ") + missed[k];
  return out + " is not in it";
}

std::optional<PanoramaPlacement> read_gpano(const std::string& path, int width, int height) {
  init_exiv2();
  try {
    auto image = Exiv2::ImageFactory::open(path);
    image->readMetadata();
    const GPanoFields g{path, image->xmpData()};
    if (!g.has("CroppedAreaImageWidthPixels") && !g.has("FullPanoWidthPixels")) return std::nullopt;
    return placement_from(g, width, height);
  } catch (const Exiv2::Error& e) {
    throw InputError(path, fmt::format("its metadata could not be read: {}", e.what()));
  }
}

CubeMap cube_from_panorama(const Image& img, const PanoramaPlacement& p, double yaw_deg, int n, double* coverage,
                           int ss, std::vector<bool>* covered) {
  CubeMap cube(n);
  std::vector<char> seen_texel(std::size_t(6) * std::size_t(n) * std::size_t(n), 0);
  const float c = float(std::cos(-deg_to_rad(yaw_deg))), s = float(std::sin(-deg_to_rad(yaw_deg)));
  const bool wrap_x = std::abs(p.full_width - img.width) < 0.5;
  const std::vector<double> omega = face_solid_angles(n);
  std::vector<double> seen_sr(std::size_t(6 * n), 0.0);  // per face row
  tbb::parallel_for(0, 6 * n, [&](int row) {
    const int f = row / n, j = row % n;
    for (int i = 0; i < n; ++i) {
      Rgb sum = Rgb::Zero();
      int seen = 0;
      for (int b = 0; b < ss; ++b)
        for (int a = 0; a < ss; ++a) {
          const float u = (float(i) + (float(a) + 0.5f) / float(ss)) / float(n);
          const float v = (float(j) + (float(b) + 0.5f) / float(ss)) / float(n);
          const Vec3f d_pano = turned_about_y(face_to_direction(f, u, v).normalized(), c, s);
          const ImagePoint q = image_point(d_pano, p, img.width, img.height);
          sum += bilinear_wrapped(img, q.x, q.y, wrap_x);
          seen += q.seen;
        }
      cube.set_texel(f, i, j, sum / float(ss * ss));
      seen_texel[texel_index(f, i, j, n)] = seen > 0;
      seen_sr[std::size_t(row)] += omega[std::size_t(j * n + i)] * seen / (ss * ss);
    }
  });
  cube.update_borders();
  if (coverage) {
    double total = 0;
    for (double w : seen_sr) total += w;
    *coverage = total / (4 * kPi);
  }
  if (covered) {
    covered->clear();
    if (std::find(seen_texel.begin(), seen_texel.end(), 0) != seen_texel.end())
      covered->assign(seen_texel.begin(), seen_texel.end());
  }
  return cube;
}

}  // namespace insitu
