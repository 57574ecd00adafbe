// recip_table: the reciprocal unit's result and relative error for every legal
// 10.4 operand, as CSV, for plotting against Figures 4, 5 and 7 of Crisu et al.
//
//   recip_table --method 3 > method3.csv
//
// stdout: the header "x_raw,x,reciprocal,relative_error", then one line per
// raw operand 1..16383 (x = x_raw / 16; reciprocal is the unit's 5.16 result;
// relative_error is the paper's eq. 3, signed, as a fraction, not percent).
// Every number is printed in its shortest exact round-trip form.
// stderr: a summary in '#' comment lines (max and mean |relative error|), so
// stdout stays plain CSV.
#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>

#include "guarded_main.h"
#include "raster/datapath/reciprocal.h"

namespace {

using tessera::raster::RecipMethod;

std::string shortest(double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc{} ? std::string(buffer, end) : std::string("nan");
}

}  // namespace

static int run_main(int argc, char** argv) {
  CLI::App app{"Reciprocal unit of the rasterizer: 1/X and its relative error for every 10.4 operand"};
  std::string method_name;
  app.add_option("-m,--method", method_name, "1, 2, 3 or method1, method2, method3 (Crisu et al., Section IV)")
      ->required()
      ->check(CLI::Validator(
          [](std::string& text) {
            return tessera::raster::parse_recip_method(text) ? std::string{}
                                                             : "unknown method '" + text + "'; use 1, 2 or 3";
          },
          "METHOD", "reciprocal method"));
  CLI11_PARSE(app, argc, argv);
  const RecipMethod method = *tessera::raster::parse_recip_method(method_name);

  std::printf("x_raw,x,reciprocal,relative_error\n");
  double max_abs = 0.0;
  double sum_abs = 0.0;
  unsigned worst_raw = 0;
  for (uint32_t raw = 1; raw <= tessera::raster::RECIP_OPERAND_MAX; ++raw) {
    const auto x_raw = static_cast<uint16_t>(raw);
    const double x = raw / 16.0;
    const double approx = tessera::raster::reciprocal_value(x_raw, method);
    const double exact = 1.0 / x;
    const double error = (approx - exact) / exact;
    std::printf("%u,%s,%s,%s\n", raw, shortest(x).c_str(), shortest(approx).c_str(), shortest(error).c_str());
    sum_abs += std::fabs(error);
    if (std::fabs(error) > max_abs) {
      max_abs = std::fabs(error);
      worst_raw = raw;
    }
  }
  const double mean_abs = sum_abs / tessera::raster::RECIP_OPERAND_MAX;
  std::fprintf(stderr, "# %s: %u operands\n", std::string(tessera::raster::to_string(method)).c_str(),
               static_cast<unsigned>(tessera::raster::RECIP_OPERAND_MAX));
  std::fprintf(stderr, "# max |relative error| = %.6f%% at x_raw %u\n", max_abs * 100.0, worst_raw);
  std::fprintf(stderr, "# mean |relative error| = %.6f%%\n", mean_abs * 100.0);
  return std::fflush(stdout) == 0 ? 0 : 1;
}

int main(int argc, char** argv) {
  return tessera::guarded_main("recip_table", [&] { return run_main(argc, argv); });
}
