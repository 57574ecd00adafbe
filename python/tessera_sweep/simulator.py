"""soc_sim as the sweep sees it: its version, its applications, its
configuration check (--print-config applies every --set and exits 2 naming a
bad key or value) and one run."""

from __future__ import annotations

import json
import subprocess
import time
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path


class SimulatorError(RuntimeError):
    pass


def set_value(value) -> str:
    """A value as soc_sim's --set key=value reads it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def set_flags(settings: dict) -> list[str]:
    flags = []
    for key, value in settings.items():
        flags += ["--set", f"{key}={set_value(value)}"]
    return flags


def flatten(tree: dict, prefix: str = "") -> dict:
    """Nested mappings to dotted keys; lists stay values."""
    flat = {}
    for key, value in tree.items():
        if isinstance(value, dict):
            flat.update(flatten(value, f"{prefix}{key}."))
        else:
            flat[f"{prefix}{key}"] = value
    return flat


@dataclass(frozen=True)
class RunResult:
    status: int
    error: str | None
    wall_s: float


class Simulator:
    def __init__(self, path: str | Path):
        self.path = Path(path).resolve()
        if not self.path.is_file():
            raise SimulatorError(f"soc_sim not found at {self.path} (build it, or pass --soc-sim)")

    def _call(self, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(self.path), *args], capture_output=True, text=True)

    @cached_property
    def version(self) -> str:
        """'0.1.0, commit 205a290': part of every cache key."""
        done = self._call("--version")
        if done.returncode != 0:
            raise SimulatorError(f"{self.path} --version failed: {done.stderr.strip()}")
        return done.stdout.strip().removeprefix("soc_sim (tessera) ")

    @cached_property
    def apps(self) -> list[str]:
        done = self._call("--list-apps")
        return [line.split()[0] for line in done.stdout.splitlines() if line.strip()]

    @cached_property
    def default_config(self) -> dict:
        return self.config({})

    def config(self, settings: dict) -> dict:
        """The effective configuration with these --set values, as soc_sim
        checks and prints it; SimulatorError with soc_sim's message if not."""
        done = self._call("--print-config", *set_flags(settings))
        if done.returncode != 0:
            raise SimulatorError(done.stderr.strip() or f"exit status {done.returncode}")
        return json.loads(done.stdout)

    def run(self, settings: dict, args: list[str], out_dir: Path, write_frames: bool) -> RunResult:
        command = [str(self.path), *set_flags(settings), "--out", str(out_dir), "--force", "-q"]
        if not write_frames:
            command.append("--no-frames")
        if args:
            command += ["--", *args]
        start = time.monotonic()
        done = subprocess.run(command, capture_output=True, text=True)
        wall_s = time.monotonic() - start
        error = None
        if done.returncode != 0:
            error = done.stderr.strip()[-2000:] or f"exit status {done.returncode}"
        return RunResult(done.returncode, error, wall_s)
