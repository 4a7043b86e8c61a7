// The pixels of every channel of an image file, with the channel count last: equal for two files
// whose pixels are equal bit for bit (the files themselves differ: OpenImageIO stamps the time).
#pragma once
#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

namespace insitu::test {

inline std::vector<float> exr_pixels(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> v(std::size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, v.data());
  v.push_back(float(spec.nchannels));
  return v;
}

// One named channel of an EXR ("objects.A"), row by row; empty when the file or channel is missing.
inline std::vector<float> exr_channel(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  const int c = spec.channelindex(name);
  if (c < 0) return {};
  std::vector<float> v(std::size_t(spec.width) * spec.height);
  in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, v.data());
  return v;
}

}  // namespace insitu::test
