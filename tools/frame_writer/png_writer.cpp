#include "png_writer.h"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <new>
#include <stdexcept>

#include "output_file.h"

namespace tessera {

namespace {

// What libpng's callbacks reach: the bytes so far and the first error.
struct Encoding {
  std::vector<unsigned char>* bytes = nullptr;
  char error[256] = {};
};

void append_bytes(png_structp png, png_bytep data, size_t length) {
  auto* encoding = static_cast<Encoding*>(png_get_io_ptr(png));
  try {
    encoding->bytes->insert(encoding->bytes->end(), data, data + length);
  } catch (const std::bad_alloc&) {
    png_error(png, "out of memory");
  }
}

void flush_nothing(png_structp /*png*/) {}

void note_error(png_structp png, png_const_charp message) {
  auto* encoding = static_cast<Encoding*>(png_get_error_ptr(png));
  std::strncpy(encoding->error, message, sizeof encoding->error - 1);
  png_longjmp(png, 1);
}

void ignore_warning(png_structp /*png*/, png_const_charp /*message*/) {}

// libpng reports errors by longjmp to the setjmp below: this function holds
// no object with a destructor between the two, only plain pointers.
bool encode(Encoding& encoding, unsigned width, unsigned height, const uint8_t* rgba) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &encoding, note_error, ignore_warning);
  if (png == nullptr) {
    std::strncpy(encoding.error, "libpng cannot start", sizeof encoding.error - 1);
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    std::strncpy(encoding.error, "libpng cannot start", sizeof encoding.error - 1);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {  // NOLINT(cert-err52-cpp): libpng's error protocol
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &encoding, append_bytes, flush_nothing);
  // Fast compression: frames are written during the simulation, and the
  // default level costs more than simulating a frame (bench/).
  png_set_compression_level(png, 1);
  // No row filter: libpng's adaptive choice tries all five per row and
  // costs more than the compression; rendered frames with flat backgrounds
  // come out no larger without it (measured on the teapot).
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  // The image's origin, as the OpenImageIO writer stored it: files stay
  // byte-identical to those of earlier runs.
  png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
  png_write_info(png, info);
  for (unsigned y = 0; y < height; ++y) png_write_row(png, rgba + size_t{y} * width * 4);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::vector<unsigned char> encode_png(unsigned width, unsigned height, const std::vector<uint8_t>& rgba) {
  if (rgba.size() != size_t{width} * height * 4)
    throw std::invalid_argument("encode_png: pixel buffer does not match the size");
  if (width == 0 || height == 0) throw std::invalid_argument("encode_png: an image of no pixels");
  std::vector<unsigned char> png;
  png.reserve(rgba.size() / 4);
  Encoding encoding;
  encoding.bytes = &png;
  if (!encode(encoding, width, height, rgba.data()))
    throw std::runtime_error(std::string("cannot encode a PNG: ") + encoding.error);
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

}  // namespace tessera
