#include "frame_writer.h"

#include <stdexcept>

#include <OpenImageIO/imageio.h>

namespace tessera {

Image read_image(const std::string& path) {
  // The pixels as stored, as write_png stores them: by default OpenImageIO
  // multiplies colour by alpha, which changes every pixel whose alpha is not
  // 255 (an antialiased fringe) and hides the colour where alpha is 0.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image image;
  image.width = static_cast<unsigned>(spec.width);
  image.height = static_cast<unsigned>(spec.height);
  std::vector<uint8_t> raw(size_t{image.width} * image.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data()))
    throw std::runtime_error("cannot read " + path + ": " + in->geterror());
  image.rgba.resize(size_t{image.width} * image.height * 4);
  for (size_t i = 0; i < size_t{image.width} * image.height; ++i) {
    for (int c = 0; c < 4; ++c) {
      uint8_t v = 255;
      if (c < spec.nchannels)
        v = raw[i * spec.nchannels + c];
      else if (c < 3)
        v = raw[i * spec.nchannels];  // grey
      image.rgba[i * 4 + c] = v;
    }
  }
  return image;
}

}  // namespace tessera
