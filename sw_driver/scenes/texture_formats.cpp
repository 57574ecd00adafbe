// Every texture format glTexImage2D takes in OpenGL ES 1.1 and the ten
// paletted formats of OES_compressed_paletted_texture, one cell each in a
// grid of 6 x 3: LUMINANCE, ALPHA, LUMINANCE_ALPHA, RGB and RGBA with
// GL_UNSIGNED_BYTE, RGB with 5_6_5, RGBA with 4_4_4_4 and 5_5_5_1, then
// PALETTE4_* and PALETTE8_* (RGB8, RGBA8, R5_G6_B5, RGBA4, RGB5_A1). The
// last paletted texture carries its whole mipmap chain (a negative level)
// and is drawn with a mipmap filter, so it is drawn textured only if every
// level arrived. Each cell holds the same 8 x 8 image twice, magnified a
// whole number of times (as many as the cell allows) with GL_NEAREST: above with GL_MODULATE by a tinted, translucent
// vertex colour, below with GL_REPLACE, both blended over the background,
// so that the missing components of each base format (ES 1.1 table 3.15)
// show. No arguments.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int SIZE = 8;  // texels a side
constexpr int COLUMNS = 6;
constexpr int CELLS = 18;

struct Cell {
  GLenum format, type;  // format 0: paletted, `type` is the compressed format
};

const Cell CELL_FORMATS[CELLS] = {
    {GL_LUMINANCE, GL_UNSIGNED_BYTE},
    {GL_ALPHA, GL_UNSIGNED_BYTE},
    {GL_LUMINANCE_ALPHA, GL_UNSIGNED_BYTE},
    {GL_RGB, GL_UNSIGNED_BYTE},
    {GL_RGBA, GL_UNSIGNED_BYTE},
    {GL_RGB, GL_UNSIGNED_SHORT_5_6_5},
    {GL_RGBA, GL_UNSIGNED_SHORT_4_4_4_4},
    {GL_RGBA, GL_UNSIGNED_SHORT_5_5_5_1},
    {0, GL_PALETTE4_RGB8_OES},
    {0, GL_PALETTE4_RGBA8_OES},
    {0, GL_PALETTE4_R5_G6_B5_OES},
    {0, GL_PALETTE4_RGBA4_OES},
    {0, GL_PALETTE4_RGB5_A1_OES},
    {0, GL_PALETTE8_RGB8_OES},
    {0, GL_PALETTE8_RGBA8_OES},
    {0, GL_PALETTE8_R5_G6_B5_OES},
    {0, GL_PALETTE8_RGBA4_OES},
    {0, GL_PALETTE8_RGB5_A1_OES},
};

// A palette entry's format and type, by the compressed format's place in
// each group of five (RGB8, RGBA8, R5_G6_B5, RGBA4, RGB5_A1).
const GLenum ENTRY_FORMAT[5] = {GL_RGB, GL_RGBA, GL_RGB, GL_RGBA, GL_RGBA};
const GLenum ENTRY_TYPE[5] = {GL_UNSIGNED_BYTE, GL_UNSIGNED_BYTE, GL_UNSIGNED_SHORT_5_6_5, GL_UNSIGNED_SHORT_4_4_4_4,
                              GL_UNSIGNED_SHORT_5_5_5_1};
const GLfloat QUAD_ST[] = {0, 0, 1, 0, 1, 1, 0, 1};
const GLushort QUAD_TRIANGLES[] = {0, 1, 2, 0, 2, 3};

GLuint g_textures[CELLS] = {};
int g_width = 0, g_height = 0;

// The image: RGBA8 per texel, every channel varying.
void texel(int i, int j, GLubyte out[4]) {
  out[0] = static_cast<GLubyte>(30 + i * 32);
  out[1] = static_cast<GLubyte>(30 + j * 32);
  out[2] = static_cast<GLubyte>(250 - (i + j) * 15);
  out[3] = static_cast<GLubyte>(255 - ((i * 3 + j * 5) % 8) * 30);
}

// Rounded to a component of `bits` bits.
unsigned narrow(unsigned value, unsigned bits) {
  const unsigned max = (1u << bits) - 1;
  return (value * max + 127) / 255;
}

// One pixel of `format` / `type` appended to `out`.
void append_pixel(GLenum format, GLenum type, const GLubyte c[4], std::vector<GLubyte>& out) {
  uint16_t word = 0;
  switch (type) {
    case GL_UNSIGNED_SHORT_5_6_5:
      word = static_cast<uint16_t>(narrow(c[0], 5) << 11 | narrow(c[1], 6) << 5 | narrow(c[2], 5));
      break;
    case GL_UNSIGNED_SHORT_4_4_4_4:
      word =
          static_cast<uint16_t>(narrow(c[0], 4) << 12 | narrow(c[1], 4) << 8 | narrow(c[2], 4) << 4 | narrow(c[3], 4));
      break;
    case GL_UNSIGNED_SHORT_5_5_5_1:
      word = static_cast<uint16_t>(narrow(c[0], 5) << 11 | narrow(c[1], 5) << 6 | narrow(c[2], 5) << 1 |
                                   (c[3] >= 128 ? 1 : 0));
      break;
    default:
      switch (format) {
        case GL_LUMINANCE: out.push_back(c[0]); break;
        case GL_ALPHA: out.push_back(c[3]); break;
        case GL_LUMINANCE_ALPHA: out.insert(out.end(), {c[0], c[3]}); break;
        case GL_RGB: out.insert(out.end(), {c[0], c[1], c[2]}); break;
        default: out.insert(out.end(), {c[0], c[1], c[2], c[3]});
      }
      return;
  }
  // A packed pixel is one 16-bit word in the host's byte order.
  const auto* bytes = reinterpret_cast<const GLubyte*>(&word);
  out.insert(out.end(), {bytes[0], bytes[1]});
}

// A paletted image of the 8 x 8 picture and `levels` levels: palette entries
// p from the picture's colours, indices (i + 2 j) mod entries, the smaller
// levels with indices of their own.
std::vector<GLubyte> paletted_image(GLenum format, int levels) {
  const unsigned code = format - GL_PALETTE4_RGB8_OES;
  const int bits = code < 5 ? 4 : 8, entries = 1 << bits;
  std::vector<GLubyte> data;
  for (int p = 0; p < entries; ++p) {
    GLubyte c[4];
    texel(p % SIZE, (p / SIZE) % SIZE, c);
    append_pixel(ENTRY_FORMAT[code % 5], ENTRY_TYPE[code % 5], c, data);
  }
  for (int level = 0; level < levels; ++level) {
    const int side = SIZE >> level;
    std::vector<unsigned> indices;
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) indices.push_back(static_cast<unsigned>(i + 2 * j + 3 * level) % entries);
    if (bits == 8) {
      for (unsigned index : indices) data.push_back(static_cast<GLubyte>(index));
    } else {
      for (size_t n = 0; n < indices.size(); n += 2) {
        const unsigned second = n + 1 < indices.size() ? indices[n + 1] : 0;
        data.push_back(static_cast<GLubyte>(indices[n] << 4 | second));
      }
    }
  }
  return data;
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("texture_formats", args, error)) return false;
  g_width = width;
  g_height = height;
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthof(0.0f, static_cast<GLfloat>(width), 0.0f, static_cast<GLfloat>(height), -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.2f, 0.35f, 0.3f, 1.0f);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  // Rows of 1, 2 and 3 bytes are not padded.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);

  glGenTextures(CELLS, g_textures);
  for (int k = 0; k < CELLS; ++k) {
    glBindTexture(GL_TEXTURE_2D, g_textures[k]);
    const Cell& cell = CELL_FORMATS[k];
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    if (cell.format != 0) {
      std::vector<GLubyte> pixels;
      for (int j = 0; j < SIZE; ++j)
        for (int i = 0; i < SIZE; ++i) {
          GLubyte c[4];
          texel(i, j, c);
          append_pixel(cell.format, cell.type, c, pixels);
        }
      glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(cell.format), SIZE, SIZE, 0, cell.format, cell.type,
                   pixels.data());
    } else {
      // The last one with its four levels (level -3: 8, 4, 2, 1) and a mipmap filter.
      const int levels = k == CELLS - 1 ? 4 : 1;
      const std::vector<GLubyte> data = paletted_image(cell.type, levels);
      glCompressedTexImage2D(GL_TEXTURE_2D, 1 - levels, cell.type, SIZE, SIZE, 0, static_cast<GLsizei>(data.size()),
                             data.data());
      if (levels > 1) glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    }
  }
  glEnable(GL_TEXTURE_2D);
  return true;
}

void draw(int) {
  glClear(GL_COLOR_BUFFER_BIT);
  const int cell_width = g_width / COLUMNS, cell_height = g_height / (CELLS / COLUMNS);
  // Pixels per texel: two quads and three gaps of 4 pixels fit a cell.
  const int scale = std::max(1, std::min((cell_width - 4) / SIZE, (cell_height - 12) / (2 * SIZE)));
  const int quad = SIZE * scale;
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glTexCoordPointer(2, GL_FLOAT, 0, QUAD_ST);
  for (int k = 0; k < CELLS; ++k) {
    glBindTexture(GL_TEXTURE_2D, g_textures[k]);
    const int x = (k % COLUMNS) * cell_width + (cell_width - quad) / 2;
    const int row_top = g_height - (k / COLUMNS) * cell_height;
    for (int half = 0; half < 2; ++half) {
      const int y = row_top - 4 - (half + 1) * quad - half * 4;
      const GLfloat x0 = static_cast<GLfloat>(x), x1 = static_cast<GLfloat>(x + quad);
      const GLfloat y0 = static_cast<GLfloat>(y), y1 = static_cast<GLfloat>(y + quad);
      const GLfloat xyz[] = {x0, y0, 0, x1, y0, 0, x1, y1, 0, x0, y1, 0};
      glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, half == 0 ? GL_MODULATE : GL_REPLACE);
      glColor4f(1.0f, 0.8f, 0.6f, 0.75f);
      glVertexPointer(3, GL_FLOAT, 0, xyz);
      glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, QUAD_TRIANGLES);
    }
  }
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene texture_formats_scene() {
  return {"texture_formats",
          "Quads with each ES 1.1 texture format and type (LUMINANCE, ALPHA, LUMINANCE_ALPHA, RGB, RGBA, 565, "
          "4444, 5551) and the ten paletted compressed formats, under GL_MODULATE and GL_REPLACE",
          init, draw};
}

}  // namespace tessera::scenes
