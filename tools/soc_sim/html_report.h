// soc_sim --report: the one-page HTML report of a run, rendered after the
// run by the Python package under python/ (tessera_sweep.run_report, with
// the sweep report's templates) from the run's stats.json and frames. The
// Python is the one found at configure time (TESSERA_PYTHON in CMake;
// the environment variable TESSERA_PYTHON overrides it).
#pragma once

#include <string>

namespace tessera {

struct HtmlReportRequest {
  std::string stats;       // the run's stats.json
  std::string frames_dir;  // its frame_NNNN.png
  std::string output;      // the page to write (*.html)
};

// The Python that renders the report: $TESSERA_PYTHON, else the configured one.
std::string report_python();

// Runs the renderer and waits for it. Returns "" when the page is written,
// else why not ("cannot run Python '/x/python3' for the run report: No such
// file or directory; run scripts/setup.sh"); the renderer's own message (a
// missing package, named) is on stderr above.
std::string write_html_report(const HtmlReportRequest& request);

}  // namespace tessera
