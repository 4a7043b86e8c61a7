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

}  // namespace insitu::test
