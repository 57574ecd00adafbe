#include "host/iss/profile.h"

#include <cxxabi.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

namespace tessera::iss {

namespace {
constexpr const char* OUTSIDE = "(outside the symbol table)";
}

Profile::Profile(const std::vector<ElfFunction>& functions)
    : m_functions(functions), m_entries(functions.size() + 1), m_last(&m_entries.back()) {
  m_last_index = static_cast<uint32_t>(m_functions.size());
}

Profile::Entry& Profile::find(uint32_t pc) {
  Memo& memo = m_memo[(pc >> 1) % MEMO_SLOTS];
  if (memo.valid && memo.pc == pc) {
    m_last_index = memo.index;
    m_last_start = memo.start;
    m_last_size = memo.size;
    m_last = &m_entries[m_last_index];
    return *m_last;
  }
  search(pc);
  memo = {true, pc, m_last_start, m_last_size, m_last_index};
  m_last = &m_entries[m_last_index];
  return *m_last;
}

void Profile::search(uint32_t pc) {
  auto it = std::upper_bound(m_functions.begin(), m_functions.end(), pc,
                             [](uint32_t address, const ElfFunction& f) { return address < f.address; });
  if (it != m_functions.begin() && pc - std::prev(it)->address < std::prev(it)->size) {
    --it;
    m_last_index = static_cast<uint32_t>(it - m_functions.begin());
    m_last_start = it->address;
    m_last_size = it->size;
  } else {
    // Outside every function: the gap up to the next one.
    m_last_index = static_cast<uint32_t>(m_functions.size());
    m_last_start = pc;
    m_last_size = it == m_functions.end() ? 1 : it->address - pc;
  }
}

std::string Profile::demangle(const std::string& name) {
  int status = 0;
  std::unique_ptr<char, decltype(&std::free)> text(abi::__cxa_demangle(name.c_str(), nullptr, nullptr, &status),
                                                   &std::free);
  return status == 0 && text ? std::string(text.get()) : name;
}

std::vector<Profile::Row> Profile::rows() const {
  std::vector<Row> out;
  for (size_t i = 0; i < m_entries.size(); ++i) {
    if (m_entries[i].instructions == 0) continue;
    const bool outside = i == m_functions.size();
    out.push_back(
        {outside ? OUTSIDE : demangle(m_functions[i].name), outside ? 0 : m_functions[i].address, m_entries[i]});
  }
  std::stable_sort(out.begin(), out.end(), [](const Row& a, const Row& b) {
    return static_cast<double>(a.entry.cycles) + a.entry.stall_cycles >
           static_cast<double>(b.entry.cycles) + b.entry.stall_cycles;
  });
  return out;
}

std::vector<Profile::Row> Profile::top(size_t count) const {
  std::vector<Row> all = rows();
  if (all.size() > count) all.resize(count);
  return all;
}

std::vector<std::string> Profile::names() const {
  std::vector<std::string> out;
  out.reserve(m_functions.size() + 1);
  for (const ElfFunction& f : m_functions) out.push_back(demangle(f.name));
  out.emplace_back(OUTSIDE);
  return out;
}

}  // namespace tessera::iss
