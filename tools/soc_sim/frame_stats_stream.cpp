#include "frame_stats_stream.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "output_file.h"

namespace fs = std::filesystem;

namespace tessera {

namespace {

// A string no statistic holds: control characters, dumped escaped.
const char* const PLACEHOLDER_TEXT = "\x01soc_sim frames\x01";
// stats.frames' depth in the document: document { stats { frames [ record {.
constexpr int RECORD_INDENT = 6, ARRAY_CLOSE_INDENT = 4;

fs::path side_path(const fs::path& folder, const std::string& kind) {
  return folder / (".soc_sim-" + kind + "-" + std::to_string(::getpid()) + ".jsonl");
}

// Reads the next line of `file` into `line`; false at the end.
bool read_line(std::FILE* file, std::string& line) {
  line.clear();
  for (int c; (c = std::fgetc(file)) != EOF;) {
    if (c == '\n') return true;
    line.push_back(static_cast<char>(c));
  }
  return !line.empty();
}

}  // namespace

FrameStatsStream::FrameStatsStream(const fs::path& folder) {
  for (auto [side, kind] :
       {std::pair{&m_frame_side, "frames"}, {&m_driver_side, "driver"}, {&m_timing_side, "timing"}}) {
    side->path = side_path(folder, kind);
    side->file = std::fopen(side->path.c_str(), "w+");
    if (side->file == nullptr) {
      const std::string reason = std::strerror(errno);
      remove_all();
      throw std::runtime_error("cannot write '" + side->path.string() + "' (statistics per frame): " + reason);
    }
  }
}

FrameStatsStream::~FrameStatsStream() {
  remove_all();
}

void FrameStatsStream::remove_all() noexcept {
  for (Side* side : {&m_frame_side, &m_driver_side, &m_timing_side}) {
    if (side->file != nullptr) std::fclose(side->file);
    side->file = nullptr;
    if (!side->path.empty()) {
      std::error_code error;
      fs::remove(side->path, error);
    }
  }
}

void FrameStatsStream::unlink_from_other_thread() const noexcept {
  for (const Side* side : {&m_frame_side, &m_driver_side, &m_timing_side}) ::unlink(side->path.c_str());
}

void FrameStatsStream::append(Side& side, const std::string& line) {
  if (std::fwrite(line.data(), 1, line.size(), side.file) != line.size() || std::fputc('\n', side.file) == EOF)
    throw std::runtime_error("cannot write '" + side.path.string() +
                             "' (statistics per frame): " + std::strerror(errno));
}

void FrameStatsStream::add_frame(const nlohmann::json& record) {
  append(m_frame_side, record.dump());
  ++m_frames;
}

void FrameStatsStream::add_driver(const nlohmann::json& figures) {
  append(m_driver_side, figures.dump());
}

void FrameStatsStream::add_timing(double wall_seconds, double cpu_seconds) {
  append(m_timing_side, nlohmann::json::array({wall_seconds, cpu_seconds}).dump());
}

const nlohmann::json& FrameStatsStream::placeholder() {
  static const nlohmann::json value = PLACEHOLDER_TEXT;
  return value;
}

FrameStatsStream::Sums FrameStatsStream::write(const fs::path& stats_path, const std::string& document,
                                               bool wall_clock) {
  const std::string marker = placeholder().dump();
  const size_t at = document.find(marker);
  if (at == std::string::npos) throw std::logic_error("stats.json: no place for the frames");
  for (Side* side : {&m_frame_side, &m_driver_side, &m_timing_side})
    if (std::fflush(side->file) != 0 || std::ferror(side->file) != 0 || std::fseek(side->file, 0, SEEK_SET) != 0)
      throw std::runtime_error("cannot read back '" + side->path.string() + "' (statistics per frame)");

  Sums sums;
  OutputFile out(stats_path);
  out.write(std::string_view(document).substr(0, at));
  out.write(m_frames == 0 ? "[]" : "[\n");
  const std::string indent(RECORD_INDENT, ' ');
  std::string frame_line, driver_line, timing_line;
  for (size_t i = 0; i < m_frames; ++i) {
    if (!read_line(m_frame_side.file, frame_line))
      throw std::runtime_error("'" + m_frame_side.path.string() + "' ends before frame " + std::to_string(i));
    nlohmann::json record = nlohmann::json::parse(frame_line);
    // As the records were joined in memory: the driver's figures of the
    // frames it reported, wall and CPU time with --wall-clock.
    if (read_line(m_driver_side.file, driver_line)) record["driver"] = nlohmann::json::parse(driver_line);
    if (read_line(m_timing_side.file, timing_line) && wall_clock) {
      const nlohmann::json timing = nlohmann::json::parse(timing_line);
      record["wall_ns"] = timing[0].get<double>() * 1e9;
      record["cpu_ns"] = timing[1].get<double>() * 1e9;
    }
    ++sums.frames;
    const nlohmann::json& energy = record.at("energy");
    sums.energy_total_j += energy.value("total_j", 0.0);
    for (const auto& [unit, figures] : energy.at("units").items())
      sums.energy_unit_j[unit] += figures.value("total_j", 0.0);
    if (record.contains("driver")) {
      ++sums.driver_frames;
      for (const auto& [name, value] : record["driver"].items())
        if (value.is_number() && name.rfind("host_", 0) != 0) sums.driver[name] += value.get<double>();
    }
    std::string text = record.dump(2);
    std::string shifted = indent;
    shifted.reserve(text.size() + text.size() / 8);
    for (char c : text) {
      shifted.push_back(c);
      if (c == '\n') shifted += indent;
    }
    out.write(shifted);
    out.write(i + 1 < m_frames ? ",\n" : "\n");
  }
  if (m_frames != 0) out.write(std::string(ARRAY_CLOSE_INDENT, ' ') + "]");
  out.write(std::string_view(document).substr(at + marker.size()));
  out.commit();
  remove_all();
  return sums;
}

}  // namespace tessera
