#!/usr/bin/env python3
"""check_transactions.py: soc_sim --trace-transactions writes the bus's transactions, filtered.

Runs the teapot on ap-tile with the DMA and the display DMA for two frames
(under a second) three times: without a filter, with a filter
(initiator=dma, a time window, an address range), and with a bad filter.
Checks that:

- every row parses, its fields are consistent (end = start + wait +
  service, wait and service not negative, command read or write);
- unfiltered, the bytes and the wait and busy cycles per initiator add up
  to the bus's per-initiator figures in stats.json;
- filtered, every row matches the filter, and the rows are exactly the
  unfiltered rows that match it;
- a bad filter is refused with status 2 and a message naming it;
- stats.json is the same with the option as without it (but the command line).

  check_transactions.py --soc-sim build/default/bin/soc_sim [--work-dir DIR]
"""

import argparse
import csv
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

TEAPOT = ["--backend", "ap-tile", "--set", "dma.enabled=true", "--set", "display.dma=true", "--frames", "2"]
FIELDS = ["initiator", "target", "command", "address", "bytes", "start_ps", "wait_ps", "service_ps", "end_ps"]
# The window and range of the filtered run: the DMA's reads of system memory
# in the second 100 ms of the run.
WINDOW_PS = (100_000_000_000, 200_000_000_000)
ADDRESSES = (0x00000000, 0x01000000)


class Failure(Exception):
    pass


def run(soc_sim, folder, args, status=0):
    command = [soc_sim, "--out", str(folder), "-q", *args]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != status:
        raise Failure(f"{' '.join(command)}: status {result.returncode}, not {status}: {result.stderr}")
    return result


def read_rows(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames != FIELDS:
            raise Failure(f"{path}: columns {reader.fieldnames}, not {FIELDS}")
        rows = []
        for row in reader:
            try:
                r = {k: (row[k] if k in ("initiator", "target", "command") else int(row[k], 0)) for k in FIELDS}
            except ValueError as e:
                raise Failure(f"{path}: row {row} does not parse: {e}") from e
            if r["command"] not in ("read", "write"):
                raise Failure(f"bad command in {row}")
            if r["wait_ps"] < 0 or r["service_ps"] <= 0:
                raise Failure(f"negative wait or no service in {row}")
            if r["end_ps"] != r["start_ps"] + r["wait_ps"] + r["service_ps"]:
                raise Failure(f"end != start + wait + service in {row}")
            rows.append(r)
    return rows


def check_totals(rows, stats):
    bus = stats["stats"]["bus"]
    period_ps = 1e6 / bus["clock_mhz"]
    for name, figures in bus["initiators"].items():
        mine = [r for r in rows if r["initiator"] == name]
        sums = {
            "bytes": sum(r["bytes"] for r in mine),
            "wait_cycles": round(sum(r["wait_ps"] for r in mine) / period_ps),
            "busy_cycles": round(sum(r["service_ps"] for r in mine) / period_ps),
        }
        for key, value in sums.items():
            if value != figures[key]:
                raise Failure(f"{name} {key}: {value} in the rows, {figures[key]} in stats.json")


def matches(r):
    return (
        r["initiator"] == "dma"
        and WINDOW_PS[0] <= r["start_ps"] < WINDOW_PS[1]
        and ADDRESSES[0] <= r["address"] < ADDRESSES[1]
    )


def check(soc_sim, work):
    run(soc_sim, work / "plain", TEAPOT)
    plain = json.loads((work / "plain" / "stats.json").read_text())
    everything = work / "all"
    run(soc_sim, everything, [*TEAPOT, "--trace-transactions", str(everything / "tx.csv")])
    rows = read_rows(everything / "tx.csv")
    stats = json.loads((everything / "stats.json").read_text())
    check_totals(rows, stats)
    stats.pop("command_line")
    plain.pop("command_line")
    if stats != plain:
        raise Failure("stats.json differs from the run without --trace-transactions")
    print(f"unfiltered: {len(rows)} rows add up to the bus's figures per initiator")

    filtered = work / "filtered"
    spec = (
        f"{filtered / 'tx.csv'}:initiator=dma,time={WINDOW_PS[0]}ps-{WINDOW_PS[1]}ps,"
        f"addr={ADDRESSES[0]:#x}-{ADDRESSES[1]:#x}"
    )
    run(soc_sim, filtered, [*TEAPOT, "--trace-transactions", spec])
    kept = read_rows(filtered / "tx.csv")
    expected = [r for r in rows if matches(r)]
    if not expected:
        raise Failure("the filter's window holds no DMA transaction: choose another")
    if kept != expected:
        raise Failure(f"filtered: {len(kept)} rows, {len(expected)} of the unfiltered rows match the filter")
    print(f"filtered: {len(kept)} rows, exactly the matching ones")

    bad = run(soc_sim, work / "bad", [*TEAPOT, "--trace-transactions", "tx.csv:initator=dma"], status=2)
    if "initator" not in bad.stderr:
        raise Failure(f"a bad filter key is not named: {bad.stderr}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--soc-sim", required=True, help="the soc_sim binary")
    parser.add_argument("--work-dir", help="where the runs go (default: a temporary folder, removed)")
    args = parser.parse_args()
    work = pathlib.Path(args.work_dir) if args.work_dir else pathlib.Path(tempfile.mkdtemp(prefix="check_tx"))
    try:
        check(args.soc_sim, work)
    except Failure as e:
        print(f"check_transactions: {e}", file=sys.stderr)
        return 1
    finally:
        if not args.work_dir:
            shutil.rmtree(work, ignore_errors=True)
    print("check_transactions: every check passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
