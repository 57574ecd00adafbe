"""soc_sim --report, opened in headless Chromium: a short run writes its
page, Chromium loads a copy with a probe script added (every <img> decoded
with naturalWidth > 0, no script error, the tables present) and takes a
screenshot of the page itself; the page's first thumbnail is the run's
first frame, byte for byte.

Usage: check_run_report_chromium.py SOC_SIM CHROMIUM WORK_DIR [SCREENSHOT]
Exits with SKIPPED (ctest's SKIP_RETURN_CODE) when CHROMIUM is not a program."""

from __future__ import annotations

import base64
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

SKIPPED = 77
TABLES = ["blocks", "host-phases", "energy-units"]
PROBE = """<script>
window.__errors = [];
window.addEventListener("error", e => window.__errors.push(String(e.message || (e.target && e.target.src))), true);
window.addEventListener("load", () => {
  const images = Array.from(document.images);
  const broken = images.filter(i => !i.complete || i.naturalWidth === 0).map(i => i.alt);
  const marker = document.createElement("pre");
  marker.id = "render-check";
  marker.textContent = JSON.stringify({
    images: images.length, broken, errors: window.__errors,
    tables: Array.from(document.querySelectorAll("table")).map(t => t.id),
    plots: document.querySelectorAll("figure svg").length});
  document.body.appendChild(marker);
});
</script>"""


def chromium(program: str, work: Path, *args: str) -> subprocess.CompletedProcess:
    # --no-sandbox: CI runs as root; a profile of its own, so no user's is touched.
    command = [program, "--headless", "--disable-gpu", "--no-sandbox", f"--user-data-dir={work / 'profile'}", *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=60, check=True)


def main() -> int:
    soc_sim, program, work = sys.argv[1], sys.argv[2], Path(sys.argv[3]).resolve()
    screenshot = Path(sys.argv[4]) if len(sys.argv) > 4 else work / "report.png"
    if not shutil.which(program):
        print(f"SKIP: chromium not found ('{program}'): scripts/setup.sh installs it")
        return SKIPPED
    shutil.rmtree(work, ignore_errors=True)
    out = work / "out"
    run = [soc_sim, "--quiet", "--frames", "3", "--out", str(out), "--report", str(out / "report.html")]
    subprocess.run(run, check=True, env={**os.environ, "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE": "1"})
    page = (out / "report.html").read_text()
    problems = []
    first = re.search(r'src="data:image/png;base64,([^"]+)"', page)
    if not first or base64.b64decode(first.group(1)) != (out / "frame_0000.png").read_bytes():
        problems.append("the first thumbnail is not frame_0000.png")

    probed = work / "probed.html"
    probed.write_text(page.replace("<head>", "<head>\n" + PROBE, 1))
    dom = chromium(program, work, "--virtual-time-budget=5000", "--dump-dom", probed.as_uri()).stdout
    found = re.search(r'<pre id="render-check">(.*?)</pre>', dom, re.S)
    if not found:
        problems.append("the page did not finish loading (no probe result in the DOM)")
    else:
        check = json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))
        print("chromium:", check)
        if check["images"] != 3:
            problems.append(f"{check['images']} images, not the 3 frames")
        if check["broken"]:
            problems.append(f"broken images: {check['broken']}")
        if check["errors"]:
            problems.append(f"script errors: {check['errors']}")
        if check["tables"] != TABLES:
            problems.append(f"tables {check['tables']}, not {TABLES}")
        if check["plots"] < 5:
            problems.append(f"{check['plots']} plots, not the 5 expected")

    screenshot.parent.mkdir(parents=True, exist_ok=True)
    chromium(
        program,
        work,
        "--hide-scrollbars",
        "--window-size=1100,1500",
        f"--screenshot={screenshot}",
        (out / "report.html").as_uri(),
    )
    if not screenshot.exists() or screenshot.stat().st_size < 10_000:
        problems.append(f"no screenshot in {screenshot}")
    for problem in problems:
        print("FAIL:", problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
