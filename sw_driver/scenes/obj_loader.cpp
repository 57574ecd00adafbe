// OBJ loading in two passes. tinyobjloader does the parsing and
// triangulation, but it is lenient where a test load must not be: it reads an
// unparsable number as 0, skips unknown statements and faces with fewer than
// three corners, and reports a bad index with the number of the last line of
// the file. So a first pass checks every statement and reports the line at
// fault; only a file that passes is handed to tinyobjloader, with comments
// removed (it takes a '#' after a statement for part of the statement).
// The two passes must read the same file: the check splits words and lines
// as tinyobjloader does (spaces and tabs; a carriage return ends a line, so
// one inside a line is refused), accepts only numbers tinyobjloader reads in
// full (0x10 is 16 to strtod and 0 to tinyobjloader), refuses control
// characters (a NUL byte ends tinyobjloader's line early), and afterwards
// compares every position and normal tinyobjloader read with its own.
#include "scenes/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace tessera::scenes {

namespace {

// Statements of the OBJ format that are valid but draw nothing here:
// grouping, materials, lines, points and free-form geometry.
const std::unordered_set<std::string> IGNORED_STATEMENTS = {
    "g",    "o",     "s",        "mg",       "usemtl", "mtllib",     "usemap",    "maplib", "vp",   "cstype", "deg",
    "bmat", "step",  "curv",     "curv2",    "surf",   "parm",       "trim",      "hole",   "scrv", "sp",     "end",
    "con",  "bevel", "c_interp", "d_interp", "lod",    "shadow_obj", "trace_obj", "ctech",  "stech"};

struct Counts {
  long positions = 0;
  long texcoords = 0;
  long normals = 0;
  long faces = 0;
  long statements = 0;
};

// A number as tinyobjloader reads it in full: an optional sign, digits with
// an optional fraction (or a fraction alone), an optional exponent. Anything
// else (0x10, 1e, nan, 1.5f) it reads as a prefix or as 0, while strtod reads
// some of it otherwise, so it is refused.
bool is_plain_decimal(const std::string& text) {
  std::size_t i = 0;
  const std::size_t n = text.size();
  auto digits = [&] {
    const std::size_t first = i;
    while (i < n && text[i] >= '0' && text[i] <= '9') ++i;
    return i - first;
  };
  if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < n && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == n;
}

// An index as both passes read it: an optional minus and digits.
bool is_plain_index(const std::string& text) {
  const std::size_t first = !text.empty() && text[0] == '-' ? 1 : 0;
  return text.size() > first && std::all_of(text.begin() + static_cast<std::ptrdiff_t>(first), text.end(),
                                            [](char c) { return c >= '0' && c <= '9'; });
}

// Words of a statement: tinyobjloader separates them by spaces and tabs only.
std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    const std::size_t first = line.find_first_not_of(" \t", i);
    if (first == std::string::npos) break;
    const std::size_t last = std::min(line.find_first_of(" \t", first), line.size());
    words.push_back(line.substr(first, last - first));
    i = last;
  }
  return words;
}

// The numbers the validator read for one kind of element (positions or
// normals), three per statement, with the statement's line, to compare with
// what tinyobjloader read.
struct ReadNumbers {
  std::vector<float> values;
  std::vector<long> lines;
};

class Validator {
 public:
  explicit Validator(const std::string& path) : m_path(path) {}

  // Checks the whole file; returns false with *error set at the first fault.
  // Fills *statements with the file's lines, comments removed, so that line
  // numbers still match.
  bool check(const std::string& text, std::string* statements, std::string* error) {
    long line_number = 0;
    for (std::size_t start = 0; start < text.size();) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      std::string line = text.substr(start, end - start);
      start = end + 1;
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (!check_characters(line, line_number, error)) return false;
      line.erase(std::min(line.find('#'), line.size()));
      if (!check_line(line, line_number, error)) return false;
      *statements += line;
      *statements += '\n';
    }
    if (m_counts.statements == 0) return fail(0, "the file is empty: no faces to draw", error);
    if (m_counts.faces == 0) return fail(0, "no faces ('f' statements) to draw", error);
    return true;
  }

  const ReadNumbers& positions() const { return m_positions; }
  const ReadNumbers& normals() const { return m_normals; }

 private:
  bool fail(long line_number, const std::string& problem, std::string* error) const {
    *error = m_path + (line_number > 0 ? ":" + std::to_string(line_number) : std::string()) + ": " + problem;
    return false;
  }

  // Text only: a control character other than a tab (a NUL byte, a carriage
  // return inside a line, which tinyobjloader takes for a line end) is
  // refused, comments included.
  bool check_characters(const std::string& line, long line_number, std::string* error) const {
    for (std::size_t column = 0; column < line.size(); ++column) {
      const auto c = static_cast<unsigned char>(line[column]);
      if (c == '\t' || (c >= 0x20 && c != 0x7f)) continue;
      const std::string where = " in column " + std::to_string(column + 1);
      if (c == 0) return fail(line_number, "a NUL byte" + where + ": not a text file", error);
      if (c == '\r') return fail(line_number, "a carriage return inside the line" + where, error);
      char code[8];
      std::snprintf(code, sizeof code, "0x%02X", c);
      return fail(line_number, "control character " + std::string(code) + where, error);
    }
    return true;
  }

  bool check_line(const std::string& line, long line_number, std::string* error) {
    std::vector<std::string> arguments = split_words(line);
    if (arguments.empty()) return true;
    const std::string keyword = arguments.front();
    arguments.erase(arguments.begin());
    ++m_counts.statements;

    if (keyword == "v") {
      if (!check_numbers(arguments, 3, 7, "vertex", MAX_OBJ_COORDINATE, line_number, error)) return false;
      record(arguments, line_number, &m_positions);
      ++m_counts.positions;
    } else if (keyword == "vn") {
      if (!check_numbers(arguments, 3, 3, "normal", HUGE_VAL, line_number, error)) return false;
      record(arguments, line_number, &m_normals);
      ++m_counts.normals;
    } else if (keyword == "vt") {
      if (!check_numbers(arguments, 1, 3, "texture coordinate", HUGE_VAL, line_number, error)) return false;
      ++m_counts.texcoords;
    } else if (keyword == "f" || keyword == "l" || keyword == "p") {
      const std::size_t minimum = keyword == "f" ? 3 : keyword == "l" ? 2 : 1;
      if (arguments.size() < minimum)
        return fail(line_number,
                    "'" + keyword + "' needs at least " + std::to_string(minimum) + " vertices, has " +
                        std::to_string(arguments.size()),
                    error);
      if (arguments.size() > MAX_OBJ_FACE_CORNERS)
        return fail(line_number,
                    "'" + keyword + "' has " + std::to_string(arguments.size()) + " vertices, more than the limit of " +
                        std::to_string(MAX_OBJ_FACE_CORNERS),
                    error);
      for (const std::string& corner : arguments)
        if (!check_corner(corner, line_number, error)) return false;
      if (keyword == "f") ++m_counts.faces;
    } else if (IGNORED_STATEMENTS.count(keyword) == 0) {
      return fail(line_number, "not an OBJ statement: '" + keyword + "'", error);
    }
    return true;
  }

  static void record(const std::vector<std::string>& arguments, long line_number, ReadNumbers* numbers) {
    for (std::size_t i = 0; i < 3; ++i)
      numbers->values.push_back(static_cast<float>(std::strtod(arguments[i].c_str(), nullptr)));
    numbers->lines.push_back(line_number);
  }

  bool check_numbers(const std::vector<std::string>& arguments, std::size_t minimum, std::size_t maximum,
                     const std::string& what, double limit, long line_number, std::string* error) {
    if (arguments.size() < minimum || arguments.size() > maximum)
      return fail(line_number,
                  what + " needs " + std::to_string(minimum) +
                      (minimum == maximum ? "" : " to " + std::to_string(maximum)) + " numbers, has " +
                      std::to_string(arguments.size()),
                  error);
    for (const std::string& argument : arguments) {
      char* end = nullptr;
      const double value = std::strtod(argument.c_str(), &end);
      if (end == argument.c_str() || *end != '\0')
        return fail(line_number, what + " coordinate '" + argument + "' is not a number", error);
      if (!std::isfinite(value)) return fail(line_number, what + " coordinate '" + argument + "' is not finite", error);
      if (!is_plain_decimal(argument))
        return fail(line_number,
                    what + " coordinate '" + argument +
                        "' is not a plain decimal number (digits, an optional fraction and exponent)",
                    error);
      if (std::fabs(value) > limit)
        return fail(line_number, what + " coordinate " + argument + " is too large (limit " + format(limit) + ")",
                    error);
    }
    return true;
  }

  // A face corner is v, v/vt, v//vn or v/vt/vn.
  bool check_corner(const std::string& corner, long line_number, std::string* error) {
    std::vector<std::string> parts;
    for (std::size_t start = 0;;) {
      const std::size_t slash = corner.find('/', start);
      parts.push_back(corner.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
      if (slash == std::string::npos) break;
      start = slash + 1;
    }
    // The vertex and, where a slash announces it, the last part are
    // required; only the texture coordinate of v//vn may be empty.
    if (parts.size() > 3 || parts[0].empty() || parts.back().empty() || (parts.size() == 2 && parts[1].empty()))
      return fail(line_number, "malformed face corner '" + corner + "'", error);
    const char* kinds[] = {"vertex", "texture coordinate", "normal"};
    const char* plurals[] = {"vertices", "texture coordinates", "normals"};
    const long defined[] = {m_counts.positions, m_counts.texcoords, m_counts.normals};
    for (std::size_t k = 0; k < parts.size(); ++k) {
      if (parts[k].empty()) continue;
      if (!is_plain_index(parts[k])) return fail(line_number, "malformed face corner '" + corner + "'", error);
      errno = 0;
      const long index = std::strtol(parts[k].c_str(), nullptr, 10);
      // Negative indices count back from the last element defined so far.
      const long resolved = index < 0 ? defined[k] + 1 + index : index;
      if (index == 0 || errno == ERANGE || resolved < 1 || resolved > defined[k])
        return fail(line_number,
                    std::string(kinds[k]) + " index " + parts[k] + " is out of range: " + std::to_string(defined[k]) +
                        " " + (defined[k] == 1 ? kinds[k] : plurals[k]) + " defined before this line",
                    error);
    }
    return true;
  }

  static std::string format(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
  }

  std::string m_path;
  Counts m_counts;
  ReadNumbers m_positions;
  ReadNumbers m_normals;
};

// Reads the file, refusing more than MAX_OBJ_FILE_BYTES (a device such as
// /dev/zero has no size to check first). Reading stops after a NUL byte: the
// validator then names its line.
bool read_limited(const std::string& path, std::string* text, std::string* error) {
  std::error_code failure;
  if (std::filesystem::is_regular_file(path, failure)) {
    const std::uintmax_t size = std::filesystem::file_size(path, failure);
    if (!failure && size > MAX_OBJ_FILE_BYTES) {
      *error =
          path + ": " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(MAX_OBJ_FILE_BYTES);
      return false;
    }
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    *error = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  std::vector<char> buffer(64 * 1024);
  while (file) {
    file.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto got = static_cast<std::size_t>(file.gcount());
    text->append(buffer.data(), got);
    if (text->size() > MAX_OBJ_FILE_BYTES) {
      *error = path + ": more than the limit of " + std::to_string(MAX_OBJ_FILE_BYTES) + " bytes";
      return false;
    }
    if (std::memchr(buffer.data(), 0, got) != nullptr) break;
  }
  if (file.bad()) {
    *error = path + ": read error: " + std::strerror(errno);
    return false;
  }
  return true;
}

// tinyobjloader's numbers against the validator's, statement by statement:
// a number the two read differently is refused with its line.
bool agree(const std::vector<tinyobj::real_t>& parsed, const ReadNumbers& expected, const std::string& what,
           const std::string& path, std::string* error) {
  if (parsed.size() != expected.values.size()) {
    *error = path + ": tinyobjloader read " + std::to_string(parsed.size() / 3) + " " + what + "s, the check " +
             std::to_string(expected.lines.size());
    return false;
  }
  for (std::size_t i = 0; i < parsed.size(); ++i) {
    const double a = parsed[i];
    const double b = expected.values[i];
    const double tolerance =
        std::max(4.0 * std::numeric_limits<float>::epsilon() * std::max(std::fabs(a), std::fabs(b)), 1e-30);
    if (!(std::fabs(a - b) <= tolerance)) {
      std::ostringstream text;
      text << path << ":" << expected.lines[i / 3] << ": " << what << " coordinate " << (i % 3 + 1) << " is read as "
           << a << " by tinyobjloader and as " << b << " by the check; write it as a plain decimal number";
      *error = text.str();
      return false;
    }
  }
  return true;
}
}  // namespace

bool load_obj(const std::string& path, Mesh* mesh, std::string* error) {
  std::string statements;
  Validator validator(path);
  {
    std::string text;
    if (!read_limited(path, &text, error)) return false;
    if (!validator.check(text, &statements, error)) return false;
  }

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings;
  std::string errors;
  std::istringstream stream(statements);
  // Materials are ignored, so no material reader: an 'mtllib' names no file
  // to be read (it could name /dev/zero).
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, /*readMatFn=*/nullptr,
                        /*triangulate=*/true)) {
    *error = path + ": " + (errors.empty() ? "tinyobjloader failed" : errors);
    while (!error->empty() && error->back() == '\n') error->pop_back();
    return false;
  }
  if (!agree(attrib.vertices, validator.positions(), "vertex", path, error) ||
      !agree(attrib.normals, validator.normals(), "normal", path, error))
    return false;

  const long position_count = static_cast<long>(attrib.vertices.size() / 3);
  const long normal_count = static_cast<long>(attrib.normals.size() / 3);
  bool use_file_normals = true;
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& corner : shape.mesh.indices) {
      if (corner.vertex_index < 0 || corner.vertex_index >= position_count) {
        *error = path + ": vertex index " + std::to_string(corner.vertex_index + 1) + " out of range";
        return false;
      }
      if (corner.normal_index < 0 || corner.normal_index >= normal_count) {
        use_file_normals = false;
        continue;
      }
      const float* normal = &attrib.normals[3 * corner.normal_index];
      const float length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
      if (!(length > 0.0f) || !std::isfinite(length)) use_file_normals = false;
    }

  Mesh loaded;
  // Distinct (position, normal) pairs become vertices; without file normals
  // the key is the position alone, so that computed normals are smooth.
  std::unordered_map<long long, std::uint16_t> vertex_of_key;
  std::size_t distinct = 0;
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& corner : shape.mesh.indices) {
      const long long key = use_file_normals
                                ? static_cast<long long>(corner.vertex_index) * (normal_count + 1) + corner.normal_index
                                : corner.vertex_index;
      auto found = vertex_of_key.find(key);
      if (found == vertex_of_key.end()) {
        // Counted on past the limit so that the error says how many there are.
        ++distinct;
        if (distinct > MAX_MESH_VERTICES) continue;
        found = vertex_of_key.emplace(key, static_cast<std::uint16_t>(distinct - 1)).first;
        for (int axis = 0; axis < 3; ++axis)
          loaded.positions.push_back(attrib.vertices[3 * corner.vertex_index + axis]);
        if (use_file_normals) {
          const float* normal = &attrib.normals[3 * corner.normal_index];
          const float length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
          for (int axis = 0; axis < 3; ++axis) loaded.normals.push_back(normal[axis] / length);
        }
      }
      loaded.indices.push_back(found->second);
    }
  if (distinct > MAX_MESH_VERTICES) {
    *error = path + ": " + std::to_string(distinct) + " distinct vertices; 16-bit indices address at most " +
             std::to_string(MAX_MESH_VERTICES);
    return false;
  }
  if (loaded.indices.empty()) {
    *error = path + ": no triangles left after triangulation";
    return false;
  }
  if (!use_file_normals) compute_smooth_normals(&loaded);
  *mesh = std::move(loaded);
  return true;
}

}  // namespace tessera::scenes
