#include "frame_writer.h"

#include <memory>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "output_file.h"

namespace tessera {

std::vector<unsigned char> encode_png(unsigned width, unsigned height, const std::vector<uint8_t>& rgba) {
  if (rgba.size() != size_t{width} * height * 4)
    throw std::invalid_argument("encode_png: pixel buffer does not match the size");
  // Encoded in memory: OpenImageIO's PNG writer does not report every
  // failed write (a full disk left empty files behind a successful call),
  // so the bytes are written by OutputFile, which checks each one.
  std::vector<unsigned char> png;
  OIIO::Filesystem::IOVecOutput memory(png);
  auto out = OIIO::ImageOutput::create("frame.png", &memory);
  if (!out) throw std::runtime_error("cannot encode a PNG: " + OIIO::geterror());
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 4, OIIO::TypeDesc::UINT8);
  // Our pixels are not premultiplied; without this OpenImageIO divides by alpha.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  // Fast compression: frames are written during the simulation, and the
  // default level costs more than simulating a frame (bench/).
  spec.attribute("png:compressionLevel", 1);
  // No row filter (PNG_FILTER_NONE): libpng's adaptive choice tries all five
  // per row and costs more than the compression; rendered frames with flat
  // backgrounds come out no larger without it (measured on the teapot).
  spec.attribute("png:filter", 0x08);
  if (!out->open("frame.png", spec)) throw std::runtime_error("cannot encode a PNG: " + out->geterror());
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, rgba.data());
  const bool closed = out->close();
  if (!ok || !closed) throw std::runtime_error("cannot encode a PNG: " + out->geterror());
  return png;
}

void write_png(const std::string& path, unsigned width, unsigned height, const std::vector<uint8_t>& rgba) {
  if (rgba.size() != size_t{width} * height * 4)
    throw std::invalid_argument("write_png: " + path + ": pixel buffer does not match the size");
  const std::vector<unsigned char> png = encode_png(width, height, rgba);
  OutputFile file(path);
  file.write(png.data(), png.size());
  file.commit();
}

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
