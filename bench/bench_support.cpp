#include "bench_support.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "process/child_process.h"

namespace tessera::bench {

WorkFolder::WorkFolder(const std::string& work_dir, const std::string& prefix) {
  if (work_dir.empty()) {
    m_scratch.emplace(prefix);
    m_path = m_scratch->path();
  } else {
    m_path = work_dir;
    std::filesystem::create_directories(m_path);
  }
}

MinMedian min_median(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("min_median: no measurement");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return {values.front(), n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2};
}

double paired_median(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> ratios;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) ratios.push_back(a[i] / b[i]);
  return min_median(ratios).median;
}

double positive(double value, const std::string& what) {
  if (!(value > 0)) throw std::runtime_error(what + ": measured " + std::to_string(value) + ", not a positive figure");
  return value;
}

namespace fs = std::filesystem;

namespace {

std::string first_line_of(const fs::path& path, const std::string& prefix) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) return line;
  return "";
}

}  // namespace

ChildResult run_child(const std::vector<std::string>& argv, const fs::path& output_file) {
  test::ChildCommand command;
  command.argv = argv;
  command.stdout_file = output_file;
  const test::ChildResult child = test::run_child(command);
  if (!child.started) throw std::runtime_error(child.start_error);
  if (!child.exited_zero()) {
    std::string line;
    for (const auto& arg : argv) line += arg + " ";
    const std::string how =
        child.signal != 0 ? "signal " + std::to_string(child.signal) : "status " + std::to_string(child.status);
    throw std::runtime_error("failed (" + how + "): " + line);
  }
  ChildResult result;
  result.wall_s = child.wall_s;
  result.cpu_s = child.cpu_s;
  result.max_rss_kib = child.max_rss_kib;
  result.output = child.out;
  return result;
}

nlohmann::json read_json_file(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

fs::path own_directory() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::current_path() : self.parent_path();
}

std::string load_average() {
  std::istringstream fields(first_line_of("/proc/loadavg", ""));
  std::string one, five, fifteen;
  fields >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

std::string machine_summary(const std::string& load_before, double total_s) {
  std::string cpu = first_line_of("/proc/cpuinfo", "model name");
  cpu = cpu.substr(cpu.find(':') == std::string::npos ? 0 : cpu.find(':') + 2);
  char text[512];
  std::snprintf(text, sizeof text,
                "Machine: %s, %u hardware threads, %s build; load average (1, 5, 15 min) %s before, %s after; "
                "the benchmark took %.0f s.",
                cpu.c_str(), std::thread::hardware_concurrency(), TESSERA_BENCH_BUILD_TYPE, load_before.c_str(),
                load_average().c_str(), total_s);
  return text;
}

double per_frame_seconds(const nlohmann::json& document, unsigned n, const std::string& key) {
  const nlohmann::json& frames = document.at("stats").at("frames");
  if (n == 0 || frames.size() < 2 * size_t{n})
    throw std::runtime_error("soc_sim showed " + std::to_string(frames.size()) + " frames, " + std::to_string(2 * n) +
                             " needed");
  const nlohmann::json &first = frames[n - 1], &last = frames[2 * n - 1];
  if (!first.contains(key) || !last.contains(key))
    throw std::runtime_error("soc_sim's frame records have no '" + key + "' (run it with --wall-clock)");
  return (last[key].get<double>() - first[key].get<double>()) * 1e-9 / n;
}

std::string format_ms(double seconds) {
  char text[32];
  const double ms = seconds * 1e3;
  std::snprintf(text, sizeof text, ms >= 100 ? "%.0f ms" : ms >= 10 ? "%.1f ms" : "%.2f ms", ms);
  return text;
}

std::string format_min_median_ms(const std::vector<double>& seconds) {
  const MinMedian m = min_median(seconds);
  return format_ms(m.min) + " / " + format_ms(m.median);
}

std::string format_ratio(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, ratio >= 10 ? "%.0f" : ratio >= 1 ? "%.1f" : "%.2f", ratio);
  return text;
}

}  // namespace tessera::bench
