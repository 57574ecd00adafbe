// OBJ loading in two passes. tinyobjloader does the parsing and
// triangulation, but it is lenient where a test load must not be: it reads an
// unparsable number as 0, skips unknown statements and faces with fewer than
// three corners, and reports a bad index with the number of the last line of
// the file. So a first pass checks every statement and reports the line at
// fault; only a file that passes is handed to tinyobjloader, with comments
// removed (it takes a '#' after a statement for part of the statement).
#include "scenes/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
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

class Validator {
 public:
  explicit Validator(const std::string& path) : m_path(path) {}

  // Checks the whole file; returns false with *error set at the first fault.
  // Fills *statements with the file's lines, comments removed, so that line
  // numbers still match.
  bool check(std::istream& in, std::string* statements, std::string* error) {
    std::string line;
    long line_number = 0;
    while (std::getline(in, line)) {
      ++line_number;
      line.erase(std::min(line.find('#'), line.size()));
      if (!check_line(line, line_number, error)) return false;
      *statements += line;
      *statements += '\n';
    }
    if (in.bad()) return fail(0, "read error: " + std::string(std::strerror(errno)), error);
    if (m_counts.statements == 0) return fail(0, "the file is empty: no faces to draw", error);
    if (m_counts.faces == 0) return fail(0, "no faces ('f' statements) to draw", error);
    return true;
  }

 private:
  bool fail(long line_number, const std::string& problem, std::string* error) const {
    *error = m_path + (line_number > 0 ? ":" + std::to_string(line_number) : std::string()) + ": " + problem;
    return false;
  }

  bool check_line(const std::string& line, long line_number, std::string* error) {
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword)) return true;
    ++m_counts.statements;
    std::vector<std::string> arguments;
    for (std::string word; words >> word;) arguments.push_back(word);

    if (keyword == "v") {
      if (!check_numbers(arguments, 3, 7, "vertex", MAX_OBJ_COORDINATE, line_number, error)) return false;
      ++m_counts.positions;
    } else if (keyword == "vn") {
      if (!check_numbers(arguments, 3, 3, "normal", HUGE_VAL, line_number, error)) return false;
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
      for (const std::string& corner : arguments)
        if (!check_corner(corner, line_number, error)) return false;
      if (keyword == "f") ++m_counts.faces;
    } else if (IGNORED_STATEMENTS.count(keyword) == 0) {
      return fail(line_number, "not an OBJ statement: '" + keyword + "'", error);
    }
    return true;
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
      if (std::fabs(value) > limit)
        return fail(line_number, what + " coordinate " + argument + " is too large (limit " + format(limit) + ")",
                    error);
    }
    return true;
  }

  // A face corner is v, v/vt, v//vn or v/vt/vn.
  bool check_corner(const std::string& corner, long line_number, std::string* error) {
    std::vector<std::string> parts;
    std::stringstream split(corner);
    for (std::string part; std::getline(split, part, '/');) parts.push_back(part);
    if (parts.empty() || parts.size() > 3 || parts[0].empty())
      return fail(line_number, "malformed face corner '" + corner + "'", error);
    const char* kinds[] = {"vertex", "texture coordinate", "normal"};
    const char* plurals[] = {"vertices", "texture coordinates", "normals"};
    const long defined[] = {m_counts.positions, m_counts.texcoords, m_counts.normals};
    for (std::size_t k = 0; k < parts.size(); ++k) {
      if (parts[k].empty()) continue;
      char* end = nullptr;
      const long index = std::strtol(parts[k].c_str(), &end, 10);
      if (*end != '\0') return fail(line_number, "malformed face corner '" + corner + "'", error);
      // Negative indices count back from the last element defined so far.
      const long resolved = index < 0 ? defined[k] + 1 + index : index;
      if (index == 0 || resolved < 1 || resolved > defined[k])
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
};

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

}  // namespace

bool load_obj(const std::string& path, Mesh* mesh, std::string* error) {
  std::string statements;
  {
    std::ifstream file(path);
    if (!file) {
      *error = path + ": cannot open: " + std::strerror(errno);
      return false;
    }
    if (!Validator(path).check(file, &statements, error)) return false;
  }

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings;
  std::string errors;
  std::istringstream stream(statements);
  // Materials are ignored, but a missing .mtl file is only a warning.
  tinyobj::MaterialFileReader material_reader(directory_of(path));
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, &material_reader,
                        /*triangulate=*/true)) {
    *error = path + ": " + (errors.empty() ? "tinyobjloader failed" : errors);
    while (!error->empty() && error->back() == '\n') error->pop_back();
    return false;
  }

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
