#include "vcd_to_fst.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "fstapi.h"

namespace fs = std::filesystem;

namespace tessera {

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

std::string joined(const std::vector<std::string>& words, size_t from = 0) {
  std::string text;
  for (size_t i = from; i < words.size(); ++i) text += (text.empty() ? "" : " ") + words[i];
  return text;
}

// The VCD's scope and variable types, as fstapi names them; the names once.
struct ScopeType {
  const char* name;
  fstScopeType type;
};
constexpr ScopeType SCOPE_TYPES[] = {{"module", FST_ST_VCD_MODULE},
                                     {"task", FST_ST_VCD_TASK},
                                     {"function", FST_ST_VCD_FUNCTION},
                                     {"begin", FST_ST_VCD_BEGIN},
                                     {"fork", FST_ST_VCD_FORK}};
struct VarType {
  const char* name;
  fstVarType type;
};
constexpr VarType VAR_TYPES[] = {{"wire", FST_VT_VCD_WIRE},
                                 {"reg", FST_VT_VCD_REG},
                                 {"real", FST_VT_VCD_REAL},
                                 {"integer", FST_VT_VCD_INTEGER},
                                 {"parameter", FST_VT_VCD_PARAMETER},
                                 {"event", FST_VT_VCD_EVENT},
                                 {"tri", FST_VT_VCD_TRI},
                                 {"supply0", FST_VT_VCD_SUPPLY0},
                                 {"supply1", FST_VT_VCD_SUPPLY1},
                                 {"time", FST_VT_VCD_TIME}};

bool is_bit(char c) {
  return c == '0' || c == '1' || c == 'x' || c == 'X' || c == 'z' || c == 'Z';
}

}  // namespace

VcdToFst::VcdToFst(fs::path path) : m_path(std::move(path)) {
  errno = 0;
  m_writer = fstWriterCreate(m_path.c_str(), 1);
  if (m_writer == nullptr)
    throw std::runtime_error("cannot create the FST trace '" + m_path.string() + "'" +
                             (errno != 0 ? ": " + std::error_code(errno, std::generic_category()).message() : ""));
  // Identical runs give identical files: fstapi would write the wall-clock
  // date until the VCD's (blanked) $date replaces it.
  fstWriterSetDate(m_writer, "");
}

VcdToFst::~VcdToFst() {
  if (m_writer != nullptr) fstWriterClose(m_writer);
}

void VcdToFst::fail(const std::string& reason) const {
  throw std::runtime_error("cannot translate the VCD trace into '" + m_path.string() + "': VCD line " +
                           std::to_string(m_line) + ": " + reason);
}

void VcdToFst::feed(std::string_view bytes) {
  size_t start = 0;
  for (size_t i = 0; i < bytes.size(); ++i) {
    if (!is_space(bytes[i])) continue;
    if (!m_partial.empty()) {
      m_partial.append(bytes.data() + start, i - start);
      token(m_partial);
      m_partial.clear();
    } else if (i > start) {
      token(bytes.substr(start, i - start));
    }
    if (bytes[i] == '\n') ++m_line;
    start = i + 1;
  }
  m_partial.append(bytes.data() + start, bytes.size() - start);
}

void VcdToFst::token(std::string_view text) {
  if (m_body && m_section.empty())
    body_token(text);
  else
    header_token(text);
}

void VcdToFst::header_token(std::string_view text) {
  if (m_section.empty()) {
    if (text.empty() || text[0] != '$') fail("expected a $keyword, found '" + std::string(text) + "'");
    m_section = text;
    m_arguments.clear();
    return;
  }
  if (text != "$end") {
    m_arguments.emplace_back(text);
    return;
  }
  declaration_done();
  m_section.clear();
}

// A declaration ($keyword ... $end) is whole.
void VcdToFst::declaration_done() {
  const std::vector<std::string>& args = m_arguments;
  if (m_section == "$date") {
    fstWriterSetDate(m_writer, joined(args).c_str());
  } else if (m_section == "$version") {
    fstWriterSetVersion(m_writer, joined(args).c_str());
  } else if (m_section == "$timescale") {
    const std::string scale = joined(args);
    if (scale.empty() || !std::isdigit(static_cast<unsigned char>(scale[0]))) fail("bad $timescale '" + scale + "'");
    fstWriterSetTimescaleFromString(m_writer, scale.c_str());
  } else if (m_section == "$scope") {
    const auto* type = std::find_if(std::begin(SCOPE_TYPES), std::end(SCOPE_TYPES),
                                    [&](const ScopeType& t) { return args.size() == 2 && args[0] == t.name; });
    if (type == std::end(SCOPE_TYPES)) fail("bad $scope '" + joined(args) + "'");
    fstWriterSetScope(m_writer, type->type, args[1].c_str(), nullptr);
  } else if (m_section == "$upscope") {
    fstWriterSetUpscope(m_writer);
  } else if (m_section == "$var") {
    const auto* type = std::find_if(std::begin(VAR_TYPES), std::end(VAR_TYPES),
                                    [&](const VarType& t) { return args.size() >= 4 && args[0] == t.name; });
    if (type == std::end(VAR_TYPES)) fail("bad $var '" + joined(args) + "'");
    char* end = nullptr;
    const unsigned long width = std::strtoul(args[1].c_str(), &end, 10);
    if (*end != '\0' || width == 0 || width > (1u << 20)) fail("bad width in $var '" + joined(args) + "'");
    const auto known = m_variables.find(args[2]);
    const uint32_t alias = known == m_variables.end() ? 0 : known->second.handle;
    const uint32_t handle = fstWriterCreateVar(m_writer, type->type, FST_VD_IMPLICIT, static_cast<uint32_t>(width),
                                               joined(args, 3).c_str(), alias);
    if (known == m_variables.end())
      m_variables.emplace(args[2], Variable{handle, static_cast<uint32_t>(width), type->type == FST_VT_VCD_REAL});
    ++m_declared;
  } else if (m_section == "$enddefinitions") {
    m_body = true;
  } else if (m_section != "$comment") {
    fail("unknown declaration '" + m_section + "'");
  }
}

void VcdToFst::body_token(std::string_view text) {
  if (!m_pending_value.empty()) {
    emit(std::string(text), m_pending_value);
    m_pending_value.clear();
    return;
  }
  const char first = text[0];
  if (first == '#') {
    char* end = nullptr;
    const std::string digits(text.substr(1));
    errno = 0;
    const unsigned long long time = std::strtoull(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || errno != 0) fail("bad time '" + std::string(text) + "'");
    if (m_has_time && time < m_time) fail("time " + digits + " goes back from " + std::to_string(m_time));
    m_time = time;
    m_has_time = true;
    fstWriterEmitTimeChange(m_writer, m_time);
  } else if (first == '$') {
    // $dumpvars, $dumpall, $dumpon, $dumpoff only bracket value changes.
    if (text == "$comment") m_section = "$comment";
  } else if (is_bit(first)) {
    if (text.size() < 2) fail("a value change without an id: '" + std::string(text) + "'");
    emit(std::string(text.substr(1)), text.substr(0, 1));
  } else if (first == 'b' || first == 'B' || first == 'r' || first == 'R') {
    if (text.size() < 2) fail("a value change without a value: '" + std::string(text) + "'");
    m_pending_value = text;
  } else {
    fail("unknown value change '" + std::string(text) + "'");
  }
}

void VcdToFst::emit(const std::string& id, std::string_view value) {
  const auto found = m_variables.find(id);
  if (found == m_variables.end()) fail("unknown variable id '" + id + "'");
  const Variable& variable = found->second;
  const char kind = static_cast<char>(std::tolower(static_cast<unsigned char>(value[0])));
  if (variable.real != (kind == 'r'))
    fail("a " + std::string(variable.real ? "non-real" : "real") + " value for the " +
         (variable.real ? "real" : "bit") + " variable '" + id + "'");
  if (variable.real) {
    const std::string text(value.substr(1));
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') fail("bad real value '" + std::string(value) + "'");
    fstWriterEmitValueChange(m_writer, variable.handle, &number);
    return;
  }
  std::string_view bits = kind == 'b' ? value.substr(1) : value;
  if (bits.empty() || !std::all_of(bits.begin(), bits.end(), is_bit)) fail("bad value '" + std::string(value) + "'");
  // VCD leaves out leading zeros (and repeats a leading x or z): widened to
  // the variable, or its low bits kept, as fst2vcd would read it back.
  if (bits.size() > variable.width) bits.remove_prefix(bits.size() - variable.width);
  const char fill = bits[0] == '1' ? '0' : bits[0];
  m_bits.assign(variable.width - bits.size(), fill);
  m_bits.append(bits);
  for (char& c : m_bits) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  fstWriterEmitValueChange(m_writer, variable.handle, m_bits.c_str());
}

void VcdToFst::finish() {
  if (!m_partial.empty()) {
    token(m_partial);
    m_partial.clear();
  }
  if (!m_section.empty()) fail("the VCD ended inside " + m_section);
  if (!m_body) fail("the VCD ended before its $enddefinitions");
  if (!m_pending_value.empty()) fail("the VCD ended after the value '" + m_pending_value + "' without its id");
  fstWriterClose(m_writer);
  m_writer = nullptr;
  void* reader = fstReaderOpen(m_path.c_str());
  if (reader == nullptr) throw std::runtime_error("the FST trace '" + m_path.string() + "' does not read back");
  const uint64_t variables = fstReaderGetVarCount(reader);
  const uint64_t end_time = fstReaderGetEndTime(reader);
  fstReaderClose(reader);
  if (variables != m_declared || (m_has_time && end_time != m_time))
    throw std::runtime_error("the FST trace '" + m_path.string() + "' reads back with " + std::to_string(variables) +
                             " variables up to time " + std::to_string(end_time) + ", not the " +
                             std::to_string(m_declared) + " written up to " + std::to_string(m_time));
}

}  // namespace tessera
