#include "array/asm/assembler.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "array/isa/ap_isa.h"

namespace tessera::ap {

AsmError::AsmError(const std::string& file, unsigned line, const std::string& problem)
    : std::runtime_error(line == 0 ? file + ": " + problem : file + ":" + std::to_string(line) + ": " + problem),
      m_file(file),
      m_line(line),
      m_problem(problem) {}

namespace {

enum class TokenKind { name, number, punct };

struct Token {
  TokenKind kind;
  std::string text;
  int64_t number = 0;

  bool is(char punct) const { return kind == TokenKind::punct && text[0] == punct; }
};

using Tokens = std::vector<Token>;

// A literal beyond an int is a typing mistake, and keeping every literal
// and every product below 2^31 keeps the sums of a line far from int64_t's
// range.
constexpr int64_t LITERAL_LIMIT = INT_MAX;

// .rept bodies replayed beyond this many lines in all are a runaway (a
// mistyped count), far beyond any program memory the array is configured
// with, and would keep the assembler busy for minutes.
constexpr int64_t MAX_EXPANDED_LINES = 1000000;

// Parentheses are read by recursion: deeper nesting than this is refused
// rather than allowed to overflow the stack.
constexpr unsigned MAX_PARENTHESES_DEPTH = 64;

// A character as a message shows it: itself, or its code if unprintable.
std::string shown_character(char c) {
  const auto code = static_cast<unsigned char>(c);
  if (code >= 0x20 && code < 0x7f) return "'" + std::string(1, c) + "'";
  const char* const hex = "0123456789ABCDEF";
  return std::string("0x") + hex[code >> 4] + hex[code & 0xf];
}

struct LoopScope {
  std::string variable;
  unsigned level;
  unsigned start;
  unsigned line;
};

// An expression's value: a number, plus (only inside a CMEM operand) the
// loop variable added to it. The sign is kept while the expression is read,
// so `a - (b - y)` adds y; only the whole expression must add it.
struct Value {
  int64_t number = 0;
  std::optional<unsigned> loop_level;
  int loop_sign = 1;
};

// A source line that holds something, tokenized once: a .rept body is kept
// as these and replayed.
struct SourceLine {
  unsigned number;
  Tokens tokens;
};

// The name a .rept binds, while its body is replayed.
struct RepeatScope {
  std::string name;
  int64_t value;
  unsigned line;
};

// A .rept whose body is being read, up to its .endr. Inner .rept blocks
// stay in the body as lines; the replay expands them.
struct RepeatCapture {
  std::string name;
  int64_t first;
  int64_t last;
  unsigned line;
  std::vector<SourceLine> body;
  // The lines of the inner .rept blocks open at this point of the body.
  std::vector<unsigned> open_inner;
};

// An .if whose .endif has not come yet.
struct ConditionScope {
  unsigned line;
  bool taken;             // its condition held (false when its enclosing lines are skipped)
  bool enclosing_active;  // the lines around it are assembled
  bool in_else;
  size_t repeat_depth;  // the .rept bodies being replayed when it opened
  bool active() const { return enclosing_active && (in_else ? !taken : taken); }
};

// tokens[1, end) split at the commas into [begin, end) ranges; none when
// nothing follows tokens[0].
std::vector<std::pair<size_t, size_t>> split_operands(const Tokens& tokens) {
  std::vector<std::pair<size_t, size_t>> operands;
  if (tokens.size() > 1) {
    size_t begin = 1;
    for (size_t i = 1; i <= tokens.size(); ++i)
      if (i == tokens.size() || tokens[i].is(',')) {
        operands.emplace_back(begin, i);
        begin = i + 1;
      }
  }
  return operands;
}

bool is_directive(const Tokens& tokens, std::string_view name) {
  return tokens[0].kind == TokenKind::name && tokens[0].text == name;
}

// The operand fields of each pattern, as the error messages name them.
std::vector<std::string_view> operand_names(OperandPattern pattern) {
  switch (pattern) {
    case OperandPattern::none: return {};
    case OperandPattern::dab: return {"d", "a", "b"};
    case OperandPattern::da: return {"d", "a"};
    case OperandPattern::ab: return {"a", "b"};
    case OperandPattern::d: return {"d"};
    case OperandPattern::dna: return {"d", "direction", "a"};
    case OperandPattern::cond: return {"condition"};
    case OperandPattern::loop: return {"variable", "start", "step"};
  }
  return {};
}

std::optional<unsigned> register_number(const std::string& name) {
  if (name.size() < 2 || name[0] != 'r') return std::nullopt;
  unsigned number = 0;
  for (size_t i = 1; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return std::nullopt;
    // Any rN is a register name; a number that large is only ever refused.
    number = std::min(number * 10 + static_cast<unsigned>(name[i] - '0'), 1000000u);
  }
  return number;
}

bool is_name_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_name_char(char c) {
  return is_name_start(c) || (c >= '0' && c <= '9');
}

std::string describe(const Token& token) {
  return "'" + token.text + "'";
}

class Assembler {
 public:
  Assembler(const std::string& source_name, const AsmLimits& limits, const AsmDefines& defines) : m_limits(limits) {
    m_program.source_name = source_name;
    if (limits.registers == 0 || limits.registers > MAX_REGISTERS)
      throw std::invalid_argument("registers must be 1.." + std::to_string(MAX_REGISTERS) + ", not " +
                                  std::to_string(limits.registers));
    if (limits.cmem_bytes == 0 || limits.cmem_bytes > (1u << ADDRESS_BITS))
      throw std::invalid_argument("CMEM bytes must be 1.." + std::to_string(1u << ADDRESS_BITS) + ", not " +
                                  std::to_string(limits.cmem_bytes));
    if (limits.program_words == 0) throw std::invalid_argument("program words must be at least 1");
    for (const auto& [name, value] : defines) {
      const bool is_name = !name.empty() && is_name_start(name[0]) &&
                           std::all_of(name.begin(), name.end(), [](char c) { return is_name_char(c); });
      if (!is_name || register_number(name))
        throw std::invalid_argument("cannot define '" + name +
                                    "': a constant's name is letters, digits and _, not starting with a digit, "
                                    "and not a register");
      m_program.constants[name] = value;
      m_name_lines[name] = 0;
    }
  }

  Program run(std::string_view source) {
    unsigned number = 0;
    while (!source.empty()) {
      const size_t newline = source.find('\n');
      std::string_view text = source.substr(0, newline);
      source = newline == std::string_view::npos ? std::string_view{} : source.substr(newline + 1);
      m_line = ++number;
      // A NUL byte anywhere, comments included, means the file is not text.
      if (const size_t nul = text.find('\0'); nul != std::string_view::npos)
        fail("a NUL byte in column " + std::to_string(nul + 1) + ": not a text file");
      const size_t comment = std::min(text.find(';'), text.find("//"));
      Tokens tokens = tokenize(text.substr(0, comment));
      if (!tokens.empty()) feed({number, std::move(tokens)});
    }
    finish();
    return std::move(m_program);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw AsmError(m_program.source_name, m_line, repetition() + problem);
  }

  // "(in .rept x = 3, y = 0) " while a .rept body is replayed: the line
  // alone does not say which pass failed.
  std::string repetition() const {
    if (m_repeats.empty()) return "";
    std::string text = "(in .rept ";
    for (size_t i = 0; i < m_repeats.size(); ++i)
      text += (i == 0 ? "" : ", ") + m_repeats[i].name + " = " + std::to_string(m_repeats[i].value);
    return text + ") ";
  }

  // One line, from the file or from a .rept body being replayed: kept while
  // a .rept body is read, else assembled.
  void feed(const SourceLine& line) {
    if (m_capture) {
      RepeatCapture& capture = *m_capture;
      if (is_directive(line.tokens, ".rept")) {
        capture.open_inner.push_back(line.number);
      } else if (is_directive(line.tokens, ".endr")) {
        if (capture.open_inner.empty()) {
          m_line = line.number;
          if (line.tokens.size() > 1) fail("nothing may follow .endr on its line");
          RepeatCapture closed = std::move(capture);
          m_capture.reset();
          repeat(closed);
          return;
        }
        capture.open_inner.pop_back();
      }
      capture.body.push_back(line);
      return;
    }
    m_line = line.number;
    if (conditional(line.tokens) || !active()) return;
    if (is_directive(line.tokens, ".rept")) {
      open_repeat(line.tokens);
    } else if (is_directive(line.tokens, ".endr")) {
      fail(".endr without a .rept");
    } else {
      statement(line.tokens);
    }
  }

  bool active() const { return m_conditions.empty() || m_conditions.back().active(); }

  // .if, .else and .endif, read whether their lines are skipped or not (so
  // that they pair up); false for any other line. The condition is read only
  // where the lines around it are assembled, so a skipped branch may use
  // names that are defined only where it is not skipped.
  bool conditional(const Tokens& tokens) {
    if (is_directive(tokens, ".if")) {
      const bool enclosing = active();
      const bool taken =
          enclosing &&
          expression(tokens, 1, tokens.size(),
                     "the condition of .if (a constant expression: .const, or defined when assembling, ap_asm -D "
                     "NAME=VALUE)",
                     false)
                  .number != 0;
      m_conditions.push_back({m_line, taken, enclosing, false, m_repeats.size()});
      return true;
    }
    const bool is_else = is_directive(tokens, ".else");
    if (!is_else && !is_directive(tokens, ".endif")) return false;
    const std::string& name = tokens[0].text;
    if (tokens.size() > 1) fail("nothing may follow " + name + " on its line");
    if (m_conditions.empty()) fail(name + " without an .if");
    ConditionScope& scope = m_conditions.back();
    if (scope.repeat_depth != m_repeats.size())
      fail(name + " inside the body of .rept '" + m_repeats.back().name + "' (line " +
           std::to_string(m_repeats.back().line) + ") belongs to the .if at line " + std::to_string(scope.line) +
           ", outside it: close the .if inside the body");
    if (is_else) {
      if (scope.in_else)
        fail(".else after an .else: the .if at line " + std::to_string(scope.line) + " has one already");
      scope.in_else = true;
    } else {
      m_conditions.pop_back();
    }
    return true;
  }

  // `.rept NAME, FIRST, LAST`: the bounds are read here, where every name
  // the body sees from outside is defined.
  void open_repeat(const Tokens& tokens) {
    const std::vector<std::pair<size_t, size_t>> operands = split_operands(tokens);
    if (operands.size() != 3)
      fail(".rept takes 3 operands (name, first, last), not " + std::to_string(operands.size()));
    if (operands[0].second - operands[0].first != 1)
      fail(".rept: expected the name of the .rept counter, not " + describe(tokens[operands[0].first]));
    const std::string name = new_name(tokens, ".rept counter");
    const auto bound = [&](size_t index, const std::string& which) {
      const int64_t value = expression(tokens, operands[index].first, operands[index].second,
                                       "the " + which + " value of .rept '" + name + "'", false)
                                .number;
      if (value < -LITERAL_LIMIT || value > LITERAL_LIMIT)
        fail(".rept '" + name + "' has " + which + " value " + std::to_string(value) + ", beyond " +
             std::to_string(LITERAL_LIMIT) + " in magnitude");
      return value;
    };
    const int64_t first = bound(1, "first");
    const int64_t last = bound(2, "last");
    m_capture = RepeatCapture{name, first, last, m_line, {}, {}};
  }

  // The body of a closed .rept, once per value of its name.
  void repeat(const RepeatCapture& capture) {
    if (capture.body.empty()) return;
    const int64_t step = capture.first <= capture.last ? 1 : -1;
    for (int64_t value = capture.first;; value += step) {
      m_expanded_lines += static_cast<int64_t>(capture.body.size());
      if (m_expanded_lines > MAX_EXPANDED_LINES) {
        m_line = capture.line;
        fail(".rept '" + capture.name + "' would replay more than " + std::to_string(MAX_EXPANDED_LINES) +
             " lines in all (the limit of the .rept blocks of a file)");
      }
      m_repeats.push_back({capture.name, value, capture.line});
      const size_t conditions = m_conditions.size();
      for (const SourceLine& line : capture.body) feed(line);
      if (m_conditions.size() > conditions) {
        m_line = m_conditions.back().line;
        fail(".if is not closed by .endif inside the body of .rept '" + capture.name + "' (line " +
             std::to_string(capture.line) + ")");
      }
      m_repeats.pop_back();
      if (value == capture.last) break;
    }
  }

  Tokens tokenize(std::string_view text) const {
    Tokens tokens;
    size_t i = 0;
    while (i < text.size()) {
      const char c = text[i];
      if (c == ' ' || c == '\t' || c == '\r') {
        ++i;
      } else if (is_name_start(c) || c == '.') {
        const size_t begin = i++;
        while (i < text.size() && is_name_char(text[i])) ++i;
        tokens.push_back({TokenKind::name, std::string(text.substr(begin, i - begin))});
      } else if (c >= '0' && c <= '9') {
        const size_t begin = i;
        while (i < text.size() && is_name_char(text[i])) ++i;
        tokens.push_back(number(text.substr(begin, i - begin)));
      } else if (std::string_view(",[]()+-*@:").find(c) != std::string_view::npos) {
        tokens.push_back({TokenKind::punct, std::string(1, c)});
        ++i;
      } else {
        fail("unexpected character " + shown_character(c));
      }
    }
    return tokens;
  }

  Token number(std::string_view text) const {
    const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
    const unsigned base = hex ? 16 : 10;
    int64_t value = 0;
    for (size_t i = hex ? 2 : 0; i < text.size(); ++i) {
      const char c = text[i];
      int digit = -1;
      if (c >= '0' && c <= '9') digit = c - '0';
      if (hex && c >= 'a' && c <= 'f') digit = c - 'a' + 10;
      if (hex && c >= 'A' && c <= 'F') digit = c - 'A' + 10;
      if (digit < 0) fail("'" + std::string(text) + "' is not a number (decimal, or hexadecimal after 0x)");
      value = value * base + digit;
      if (value > LITERAL_LIMIT) fail("the number " + std::string(text) + " is beyond " + std::to_string(INT_MAX));
    }
    return {TokenKind::number, std::string(text), value};
  }

  void statement(const Tokens& tokens) {
    const Token& first = tokens[0];
    if (first.kind == TokenKind::name && first.text[0] != '.' && tokens.size() >= 2 && tokens[1].is(':')) {
      if (tokens.size() > 2) fail("nothing may follow the label '" + first.text + "' on its line");
      label(first.text);
    } else if (first.kind == TokenKind::name && first.text[0] == '.') {
      directive(tokens);
    } else if (first.kind == TokenKind::name) {
      const OpInfo* info = find_op(first.text);
      if (info == nullptr) fail("unknown mnemonic '" + first.text + "'");
      instruction(*info, tokens);
    } else {
      fail("expected an instruction, a directive or a label, not " + describe(first));
    }
  }

  void label(const std::string& name) {
    if (!m_repeats.empty())
      fail("label '" + name + "' inside the body of .rept '" + m_repeats.back().name + "' (line " +
           std::to_string(m_repeats.back().line) + "): it would be defined once per repetition");
    if (!m_loops.empty())
      fail("label '" + name + "' inside the body of loop '" + m_loops.back().variable + "' (line " +
           std::to_string(m_loops.back().line) + "): a label is an entry point, close the loop with endloop first");
    const auto [it, added] = m_label_lines.emplace(name, m_line);
    if (!added) fail("duplicate label '" + name + "' (first at line " + std::to_string(it->second) + ")");
    m_program.entries[name] = static_cast<unsigned>(m_program.words.size());
    m_stage = Stage::other;
    if (!m_open_entry) m_open_entry = std::make_pair(name, m_line);
    m_reachable = true;
  }

  void directive(const Tokens& tokens) {
    const std::string& name = tokens[0].text;
    if ((name == ".const" || name == ".var") && !m_repeats.empty())
      fail(name + " inside the body of .rept '" + m_repeats.back().name + "' (line " +
           std::to_string(m_repeats.back().line) +
           "): it would be defined once per repetition; define it before the .rept");
    if (name == ".const") {
      const std::string& constant = new_name(tokens, "constant");
      const Value value = expression(tokens, 2, tokens.size(), "the value of constant '" + constant + "'", false);
      if (value.number < INT_MIN || value.number > INT_MAX)
        fail("constant '" + constant + "' = " + std::to_string(value.number) + " does not fit an int");
      m_program.constants[constant] = static_cast<int>(value.number);
      m_name_lines[constant] = m_line;
    } else if (name == ".var") {
      define_variable(tokens);
    } else if (name == ".stage") {
      if (tokens.size() != 2 || tokens[1].kind != TokenKind::name) fail(".stage takes one stage name");
      const std::optional<Stage> stage = find_stage(tokens[1].text);
      if (!stage) fail("unknown stage '" + tokens[1].text + "'");
      m_stage = *stage;
    } else {
      fail("unknown directive '" + name + "'");
    }
  }

  // The name a directive or a loop defines (tokens[1]), checked against
  // every name an expression can use.
  const std::string& new_name(const Tokens& tokens, const std::string& what) const {
    if (tokens.size() < 2 || tokens[1].kind != TokenKind::name || tokens[1].text[0] == '.')
      fail(tokens[0].text + ": expected the name of the " + what);
    const std::string& name = tokens[1].text;
    if (register_number(name)) fail("'" + name + "' is a register and cannot name a " + what);
    const auto first_at = [&](unsigned found) {
      return found == 0 ? std::string(" (defined when assembling)") : " (line " + std::to_string(found) + ")";
    };
    if (m_program.constants.count(name) != 0)
      fail("duplicate name '" + name + "': already a constant" + first_at(m_name_lines.at(name)));
    if (m_program.variables.count(name) != 0)
      fail("duplicate name '" + name + "': already a variable" + first_at(m_name_lines.at(name)));
    for (const LoopScope& loop : m_loops)
      if (loop.variable == name)
        fail("duplicate name '" + name + "': already the variable of the enclosing loop" + first_at(loop.line));
    for (const RepeatScope& scope : m_repeats)
      if (scope.name == name)
        fail("duplicate name '" + name + "': already the counter of the enclosing .rept" + first_at(scope.line));
    return name;
  }

  void define_variable(const Tokens& tokens) {
    const std::string& name = new_name(tokens, "variable");
    size_t at = 2;
    while (at < tokens.size() && !tokens[at].is('@')) ++at;
    const int64_t size = expression(tokens, 2, at, "the size of variable '" + name + "'", false).number;
    if (size < 1 || size > m_limits.cmem_bytes)
      fail("variable '" + name + "' has size " + std::to_string(size) + ", not 1.." +
           std::to_string(m_limits.cmem_bytes));
    int64_t address = 0;
    if (at < tokens.size()) {
      address = expression(tokens, at + 1, tokens.size(), "the address of variable '" + name + "'", false).number;
      if (address < 0) fail("variable '" + name + "' at negative address " + std::to_string(address));
    } else {
      // The first free place at or after the end of the previous variable
      // placed this way, stepping over those placed at fixed addresses.
      address = m_next_variable;
      for (bool moved = true; moved;) {
        moved = false;
        for (const auto& [other, variable] : m_program.variables)
          if (address < variable.address + variable.size && variable.address < address + size) {
            address = variable.address + variable.size;
            moved = true;
          }
      }
      m_next_variable = static_cast<unsigned>(address + size);
    }
    if (address + size > m_limits.cmem_bytes)
      fail("variable '" + name + "' (" + std::to_string(size) + " bytes at " + std::to_string(address) +
           ") does not fit the " + std::to_string(m_limits.cmem_bytes) + " bytes of CMEM");
    for (const auto& [other, variable] : m_program.variables)
      if (address < variable.address + variable.size && variable.address < address + size)
        fail("variable '" + name + "' (bytes " + std::to_string(address) + ".." + std::to_string(address + size - 1) +
             ") overlaps variable '" + other + "' (bytes " + std::to_string(variable.address) + ".." +
             std::to_string(variable.address + variable.size - 1) + ")");
    m_program.variables[name] = {static_cast<uint16_t>(address), static_cast<uint16_t>(size)};
    m_name_lines[name] = m_line;
  }

  // An expression being read: tokens[at, end).
  struct Cursor {
    const Tokens& tokens;
    size_t at;
    size_t end;
    const std::string& what;
    bool in_address;
    unsigned depth = 0;  // of parentheses open at `at`

    bool next_is(char punct) const { return at < end && tokens[at].is(punct); }
  };

  // tokens[begin, end): sums, differences and products of numbers and
  // names, in parentheses where needed; inside a CMEM operand
  // (`in_address`) one loop variable may be added, unscaled.
  Value expression(const Tokens& tokens, size_t begin, size_t end, const std::string& what, bool in_address) const {
    if (begin >= end) fail("expected " + what);
    Cursor cursor{tokens, begin, end, what, in_address};
    const Value value = sum(cursor);
    if (cursor.at != end) {
      if (tokens[cursor.at].is(')')) fail("')' without a matching '(' in " + what);
      fail("expected +, - or * in " + what + ", not " + describe(tokens[cursor.at]));
    }
    if (value.loop_level && value.loop_sign < 0)
      fail("loop variable '" + m_loops[*value.loop_level].variable + "' subtracted in " + what +
           ": it can only be added");
    return value;
  }

  Value sum(Cursor& cursor) const {
    Value value = product(cursor);
    while (cursor.next_is('+') || cursor.next_is('-')) {
      const bool minus = cursor.tokens[cursor.at++].is('-');
      const Value term = product(cursor);
      if (term.loop_level) {
        if (value.loop_level) fail("two loop variables in " + cursor.what + ": an address adds at most one");
        value.loop_level = term.loop_level;
        value.loop_sign = minus ? -term.loop_sign : term.loop_sign;
      }
      value.number += minus ? -term.number : term.number;
    }
    return value;
  }

  Value product(Cursor& cursor) const {
    Value value = factor(cursor);
    while (cursor.next_is('*')) {
      ++cursor.at;
      const Value other = factor(cursor);
      const std::optional<unsigned> scaled = value.loop_level ? value.loop_level : other.loop_level;
      if (scaled)
        fail("loop variable '" + m_loops[*scaled].variable + "' cannot be scaled: the AC adds it to " + cursor.what +
             " as it is");
      // |a * b| <= limit exactly when |b| <= limit / |a|, with no overflow.
      const int64_t a = value.number < 0 ? -value.number : value.number;
      const int64_t b = other.number < 0 ? -other.number : other.number;
      if (a != 0 && b > LITERAL_LIMIT / a)
        fail("the product " + std::to_string(value.number) + " * " + std::to_string(other.number) + " in " +
             cursor.what + " is beyond " + std::to_string(LITERAL_LIMIT) + " in magnitude");
      value.number *= other.number;
    }
    return value;
  }

  // A number, a name or a parenthesised expression, after any signs.
  Value factor(Cursor& cursor) const {
    int sign = 1;
    while (cursor.next_is('+') || cursor.next_is('-')) sign *= cursor.tokens[cursor.at++].is('-') ? -1 : 1;
    if (cursor.at == cursor.end) fail(cursor.what + " ends with an operator");
    const Token& token = cursor.tokens[cursor.at++];
    Value value;
    if (token.kind == TokenKind::number) {
      value.number = token.number;
    } else if (token.kind == TokenKind::name) {
      value = name_value(token.text, cursor.what, cursor.in_address);
    } else if (token.is('(')) {
      if (++cursor.depth > MAX_PARENTHESES_DEPTH)
        fail("parentheses nested more than " + std::to_string(MAX_PARENTHESES_DEPTH) + " deep in " + cursor.what);
      value = sum(cursor);
      --cursor.depth;
      if (!cursor.next_is(')')) fail("'(' without a matching ')' in " + cursor.what);
      ++cursor.at;
    } else {
      fail("expected a number, a name or '(' in " + cursor.what + ", not " + describe(token));
    }
    value.number *= sign;
    value.loop_sign *= sign;
    return value;
  }

  Value name_value(const std::string& name, const std::string& what, bool in_address) const {
    Value value;
    if (const auto constant = m_program.constants.find(name); constant != m_program.constants.end()) {
      value.number = constant->second;
      return value;
    }
    if (const auto variable = m_program.variables.find(name); variable != m_program.variables.end()) {
      value.number = variable->second.address;
      return value;
    }
    for (const RepeatScope& scope : m_repeats)
      if (scope.name == name) {
        value.number = scope.value;
        return value;
      }
    for (const LoopScope& loop : m_loops) {
      if (loop.variable != name) continue;
      if (!in_address)
        fail("loop variable '" + name + "' in " + what + ": loop variables are only added to CMEM addresses");
      value.loop_level = loop.level;
      return value;
    }
    if (m_closed_loops.count(name) != 0) fail("loop variable '" + name + "' used outside its loop");
    if (m_label_lines.count(name) != 0) fail("'" + name + "' is a label, not a constant or variable");
    if (register_number(name)) fail("register " + name + " in " + what + ": expected a number or a name");
    fail("undefined name '" + name + "' in " + what);
  }

  void instruction(const OpInfo& info, const Tokens& tokens) {
    const std::string mnemonic(info.mnemonic);
    const std::vector<std::string_view> names = operand_names(info.operands);
    const std::vector<std::pair<size_t, size_t>> operands = split_operands(tokens);
    if (operands.size() != names.size()) {
      std::string expected;
      for (const std::string_view name : names) expected += (expected.empty() ? "" : ", ") + std::string(name);
      fail(mnemonic + " takes " + std::to_string(names.size()) + " operand" + (names.size() == 1 ? "" : "s") +
           (expected.empty() ? "" : " (" + expected + ")") + ", not " + std::to_string(operands.size()));
    }
    for (size_t i = 0; i < operands.size(); ++i)
      if (operands[i].first == operands[i].second)
        fail("operand " + std::string(names[i]) + " of " + mnemonic + " is missing");

    Instruction in;
    in.opcode = info.opcode;
    in.stage = m_stage;
    const auto data = [&](size_t index) {
      return data_operand(info, tokens, operands[index], names[index][0], std::string(names[index]));
    };
    const auto single_name = [&](size_t index) -> const std::string& {
      const auto [begin, end] = operands[index];
      if (end - begin != 1 || tokens[begin].kind != TokenKind::name)
        fail("operand " + std::string(names[index]) + " of " + mnemonic + " must be a name, not " +
             describe(tokens[begin]));
      return tokens[begin].text;
    };
    switch (info.operands) {
      case OperandPattern::none: break;
      case OperandPattern::dab:
        in.d = data(0);
        in.a = data(1);
        in.b = data(2);
        break;
      case OperandPattern::da:
        in.d = data(0);
        in.a = data(1);
        break;
      case OperandPattern::ab:
        in.a = data(0);
        in.b = data(1);
        break;
      case OperandPattern::d: in.d = data(0); break;
      case OperandPattern::dna: {
        in.d = data(0);
        const std::string& name = single_name(1);
        const std::optional<Direction> direction = find_direction(name);
        if (!direction) fail("unknown direction '" + name + "' (left, right, up or down)");
        in.b.value = static_cast<uint16_t>(*direction);
        in.a = data(2);
        break;
      }
      case OperandPattern::cond: {
        const std::string& name = single_name(0);
        const std::optional<Cond> cond = find_cond(name);
        if (!cond) fail("unknown condition '" + name + "'");
        in.a.value = static_cast<uint16_t>(*cond);
        break;
      }
      case OperandPattern::loop: open_loop(in, tokens, operands); return;
    }
    if (closes_loop(info.opcode)) {
      if (m_loops.empty()) fail(mnemonic + " without a loop");
      emit(in);
      m_closed_loops.insert(m_loops.back().variable);
      m_loops.pop_back();
      return;
    }
    if (info.opcode == Opcode::op_halt) {
      if (!m_loops.empty())
        fail("halt inside the body of loop '" + m_loops.back().variable + "' (line " +
             std::to_string(m_loops.back().line) + "): the AC would stop in the loop's first pass");
      emit(in);
      m_open_entry.reset();
      m_reachable = false;
      return;
    }
    emit(in);
  }

  Operand data_operand(const OpInfo& info, const Tokens& tokens, std::pair<size_t, size_t> range, char which,
                       const std::string& name) const {
    const std::string what = "operand " + name + " of " + std::string(info.mnemonic);
    const unsigned width = operand_width(info.opcode, which);
    const auto [begin, end] = range;
    Operand operand;
    const std::optional<unsigned> reg =
        end - begin == 1 && tokens[begin].kind == TokenKind::name ? register_number(tokens[begin].text) : std::nullopt;
    if (reg) {
      if (info.forms == Forms::m)
        fail(what + " must be a CMEM address: " + std::string(info.mnemonic) + " takes no registers");
      if (*reg >= MAX_REGISTERS)
        fail("'" + tokens[begin].text + "' is not a register (r0..r" + std::to_string(MAX_REGISTERS - 1) + ")");
      const std::string last = "r" + std::to_string(m_limits.registers - 1);
      if (*reg + width > m_limits.registers) {
        if (width == 1)
          fail("register r" + std::to_string(*reg) + " is beyond " + last + ", the last of " +
               std::to_string(m_limits.registers) + " registers");
        fail(what + " covers r" + std::to_string(*reg) + "..r" + std::to_string(*reg + width - 1) + ", beyond " + last +
             ", the last of " + std::to_string(m_limits.registers) + " registers");
      }
      operand.value = static_cast<uint16_t>(*reg);
      return operand;
    }
    if (!tokens[begin].is('[') || !tokens[end - 1].is(']') || end - begin < 2) {
      const std::string kinds = info.forms == Forms::r   ? "a register r0..r15"
                                : info.forms == Forms::m ? "a CMEM address [expression]"
                                                         : "a register r0..r15 or a CMEM address [expression]";
      fail(what + " must be " + kinds + ", not " + describe(tokens[begin]));
    }
    if (info.forms == Forms::r)
      fail(what + " must be a register: " + std::string(info.mnemonic) + " takes no CMEM address");
    const Value value = expression(tokens, begin + 1, end - 1, "the address of " + what, true);
    if (value.number < 0) fail(what + ": CMEM address " + std::to_string(value.number) + " is negative");
    const unsigned start = value.loop_level ? m_loops[*value.loop_level].start : 0;
    const int64_t last = value.number + start + width - 1;
    if (last >= m_limits.cmem_bytes) {
      std::string reach = "CMEM address " + std::to_string(value.number);
      if (value.loop_level)
        reach += " + " + m_loops[*value.loop_level].variable + " (up to " + std::to_string(start) + ")";
      if (width > 1) reach += " and the " + std::to_string(width - 1) + " bytes after it";
      fail(what + ": " + reach + " reaches byte " + std::to_string(last) + ", beyond the " +
           std::to_string(m_limits.cmem_bytes) + " bytes of CMEM");
    }
    operand.in_cmem = true;
    operand.value = static_cast<uint16_t>(value.number);
    operand.loop = static_cast<uint8_t>(value.loop_level ? *value.loop_level + 1 : 0);
    return operand;
  }

  void open_loop(Instruction& in, const Tokens& tokens, const std::vector<std::pair<size_t, size_t>>& operands) {
    const auto [var_begin, var_end] = operands[0];
    if (var_end - var_begin != 1 || tokens[var_begin].kind != TokenKind::name || tokens[var_begin].text[0] == '.')
      fail("loop: expected the name of the loop variable, not " + describe(tokens[var_begin]));
    // new_name() reads the name at tokens[1], which is where it is.
    const std::string name = new_name(tokens, "loop variable");
    if (m_loops.size() >= LOOP_LEVELS)
      fail("loop '" + name + "' nests " + std::to_string(m_loops.size() + 1) + " deep: the AC runs at most " +
           std::to_string(LOOP_LEVELS) + " nested loops");
    const int64_t start =
        expression(tokens, operands[1].first, operands[1].second, "the start of loop '" + name + "'", false).number;
    if (start < 0 || start > MAX_LOOP_START)
      fail("loop '" + name + "' starts at " + std::to_string(start) + ", not 0.." + std::to_string(MAX_LOOP_START));
    const int64_t step =
        expression(tokens, operands[2].first, operands[2].second, "the step of loop '" + name + "'", false).number;
    if (step < 1 || step > MAX_LOOP_START)
      fail("loop '" + name + "' has step " + std::to_string(step) + ", not 1.." + std::to_string(MAX_LOOP_START));
    in.d.value = static_cast<uint16_t>(m_loops.size());
    in.a.value = static_cast<uint16_t>(start);
    in.b.value = static_cast<uint16_t>(step);
    emit(in);
    m_loops.push_back({name, static_cast<unsigned>(m_loops.size()), static_cast<unsigned>(start), m_line});
  }

  void emit(const Instruction& in) {
    if (!m_reachable)
      fail(m_label_lines.empty() ? "instruction before the first label: no entry point reaches it"
                                 : "instruction after halt with no label before it: no entry point reaches it");
    if (m_program.words.size() >= m_limits.program_words)
      fail("the program is longer than the " + std::to_string(m_limits.program_words) + " words of program memory");
    // The decoder is the AC's: what it refuses, the assembler refuses.
    const uint64_t word = encode(in);
    const Decoded decoded = decode(word);
    if (!decoded.error.empty()) fail(decoded.error);
    if (encode(decoded.instruction) != word)
      fail(std::string(op_info(in.opcode).mnemonic) + ": an operand does not fit its field");
    const std::string beyond = check_limits(decoded.instruction, m_limits.registers, m_limits.cmem_bytes);
    if (!beyond.empty()) fail(beyond);
    m_program.words.push_back(word);
    m_program.lines.push_back(m_line);
  }

  void finish() {
    if (!m_conditions.empty()) {
      m_line = m_conditions.back().line;
      fail(".if is not closed by .endif before the end of the file");
    }
    if (m_capture) {
      m_line = m_capture->open_inner.empty() ? m_capture->line : m_capture->open_inner.back();
      fail(".rept is not closed by .endr before the end of the file");
    }
    if (!m_loops.empty()) {
      m_line = m_loops.back().line;
      fail("loop '" + m_loops.back().variable + "' is not closed by endloop before the end of the file");
    }
    if (m_open_entry) {
      m_line = m_open_entry->second;
      fail("entry '" + m_open_entry->first + "' does not reach a halt before the end of the file");
    }
  }

  Program m_program;
  AsmLimits m_limits;
  unsigned m_line = 0;
  Stage m_stage = Stage::other;
  std::vector<LoopScope> m_loops;
  std::set<std::string> m_closed_loops;
  std::map<std::string, unsigned> m_label_lines;
  std::map<std::string, unsigned> m_name_lines;
  // The .rept whose body is being read, and those being replayed, outermost
  // first.
  std::optional<RepeatCapture> m_capture;
  std::vector<RepeatScope> m_repeats;
  int64_t m_expanded_lines = 0;
  // The .if blocks open, outermost first.
  std::vector<ConditionScope> m_conditions;
  // The first label since the last halt: its code has not reached a halt yet.
  std::optional<std::pair<std::string, unsigned>> m_open_entry;
  // Whether a label precedes the next instruction with no halt between.
  bool m_reachable = false;
  unsigned m_next_variable = 0;
};

}  // namespace

Program assemble(std::string_view source, const std::string& source_name, const AsmLimits& limits,
                 const AsmDefines& defines) {
  return Assembler(source_name, limits, defines).run(source);
}

Program assemble_file(const std::string& path, const AsmLimits& limits, const AsmDefines& defines) {
  std::string source;
  std::error_code failure;
  if (std::filesystem::is_regular_file(path, failure)) {
    const std::uintmax_t size = std::filesystem::file_size(path, failure);
    if (!failure && size > MAX_SOURCE_BYTES)
      throw AsmError(path, 0,
                     std::to_string(size) + " bytes, more than the limit of " + std::to_string(MAX_SOURCE_BYTES));
  }
  try {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw AsmError(path, 0, "cannot read the file");
    // At most MAX_SOURCE_BYTES (a device such as /dev/zero has no end);
    // reading stops after a NUL byte, which assemble() then names by line.
    std::vector<char> buffer(64 * 1024);
    while (in) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const auto got = static_cast<size_t>(in.gcount());
      source.append(buffer.data(), got);
      if (source.size() > MAX_SOURCE_BYTES)
        throw AsmError(path, 0, "more than the limit of " + std::to_string(MAX_SOURCE_BYTES) + " bytes");
      if (std::find(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(got), '\0') !=
          buffer.begin() + static_cast<std::ptrdiff_t>(got))
        break;
    }
    if (in.bad()) throw AsmError(path, 0, "cannot read the file");
  } catch (const AsmError&) {
    throw;
  } catch (const std::exception& e) {
    // libstdc++ reports a read error (a folder, say) by throwing from the
    // stream buffer, whatever the stream's exception mask.
    throw AsmError(path, 0, std::string("cannot read the file (") + e.what() + ")");
  }
  return assemble(source, path, limits, defines);
}

}  // namespace tessera::ap
