#include "bench_support.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace tessera::bench {

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
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const auto& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int error = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(error));
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed for " + argv[0]);
  ChildResult result;
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.max_rss_kib = usage.ru_maxrss;
  result.cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                 static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
  std::ifstream in(output_file);
  std::stringstream text;
  text << in.rdbuf();
  result.output = text.str();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string command;
    for (const auto& arg : argv) command += arg + " ";
    throw std::runtime_error("failed (status " + std::to_string(status) + "): " + command);
  }
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
