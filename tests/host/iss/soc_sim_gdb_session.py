"""GDB (gdb-multiarch, batch mode) against soc_sim --gdb: the ISS in the SoC.

    soc_sim_gdb_session.py SOC_SIM APPS_ELF FAULT_ELF WORK_DIR

APPS_ELF is bin/arm922t/tessera_apps.elf (soc_sim runs it for a built-in
application with host.model=iss), FAULT_ELF tests/host/iss_programs'
fault_1.elf (an undefined instruction at 0x60). Each run is the triangle
scene, two frames, on the ISS:

- a run without GDB, the reference;
- GDB at a breakpoint on the display driver's present(): the PC at the
  function, SP in the program's stacks, supervisor mode in ARM state; the
  driver's frame buffers (memory at r0, the `this` pointer) where the boot
  loader's layout puts them, computed here from --print-config; the first
  frame buffer's contents read through GDB equal to the reference's first
  frame; a register and a word of dead stack written and read back; two
  single steps; the breakpoint deleted and the program continued to its
  exit. soc_sim's frames and statistics must equal the reference's: GDB
  does not disturb the simulation;
- GDB killing the program at the breakpoint (soc_sim fails naming the PC);
- GDB continuing into the fault program's undefined instruction (a stop
  with SIGILL at its address, then the launcher's error);
- bad input: --gdb with host.model=native, a port in use, a client that
  connects and goes away without a word (the program runs on).

Every process has a timeout: the test never hangs. Exit status 0 when every
check passes; 1, with each failure printed, when one does not.
"""

import json
import os
import pathlib
import re
import socket
import struct
import subprocess
import sys
import time

# The PNG reader shared with scripts/ (scripts/png_read.py).
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[3] / "scripts"))
import png_read  # noqa: E402

TIMEOUT_S = 40  # any one process
PORT_WAIT_S = 20  # for soc_sim to write its port file

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED: " + message)
    return condition


def run(command):
    return subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT_S)


class Server:
    """soc_sim --gdb 0, in the background, until it has written its port."""

    def __init__(self, soc_sim, out, arguments):
        port_file = out + ".port"
        if os.path.exists(port_file):
            os.remove(port_file)
        self.out = out
        self.stdout = open(out + ".stdout", "w")
        self.stderr = open(out + ".stderr", "w")
        self.process = subprocess.Popen(
            [soc_sim, *arguments, "--out", out, "--gdb", "0", "--gdb-port-file", port_file],
            stdout=self.stdout,
            stderr=self.stderr,
        )
        deadline = time.monotonic() + PORT_WAIT_S
        self.port = None
        while time.monotonic() < deadline and self.process.poll() is None:
            if os.path.exists(port_file) and open(port_file).read().strip():
                self.port = int(open(port_file).read())
                break
            time.sleep(0.05)

    def finish(self):
        try:
            status = self.process.wait(timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self.process.kill()
            status = self.process.wait()
            check(False, f"soc_sim ({self.out}) did not finish within {TIMEOUT_S} s")
        self.stdout.close()
        self.stderr.close()
        return status, open(self.out + ".stderr").read()


def gdb(elf, port, commands):
    command = [
        "gdb-multiarch",
        "-nx",
        "-batch",
        elf,
        "-ex",
        "set pagination off",
        "-ex",
        f"target remote 127.0.0.1:{port}",
    ]
    for line in commands:
        command += ["-ex", line]
    try:
        result = run(command)
    except subprocess.TimeoutExpired as timeout:
        check(False, f"gdb did not finish within {TIMEOUT_S} s")
        return (timeout.stdout or b"").decode() if isinstance(timeout.stdout, bytes) else (timeout.stdout or "")
    print(result.stdout + result.stderr)
    return result.stdout + result.stderr


def read_png_rgba(path):
    """The pixels of an 8-bit RGBA PNG (what soc_sim writes), as rows of bytes."""
    width, height, channels, rows = png_read.read_png(path)
    assert channels == 4, f"{path}: not an RGBA PNG"
    return width, height, rows


def rgb565_of_png(path):
    """The frame as the RGB565 frame buffer it was shown from: the top bits of
    each channel, whatever the display's expansion to 8 bits."""
    width, height, rows = read_png_rgba(path)
    out = bytearray()
    for row in rows:
        for x in range(width):
            r, g, b = row[4 * x], row[4 * x + 1], row[4 * x + 2]
            out += struct.pack("<H", (r >> 3) << 11 | (g >> 2) << 5 | (b >> 3))
    return bytes(out)


def frame_buffers(soc_sim, scene):
    """The boot loader's layout (contract/soc/software_layout.h), worked out here
    from the configuration: the two frame buffers at the top of system memory
    (at address 0, mem.size_mib of it), each rounded up to 4 KiB."""
    config = json.loads(run([soc_sim, *scene, "--print-config"]).stdout)
    bytes_per_pixel = {"rgb565": 2, "rgba8888": 4}[config["display"]["format"]]
    frame = config["display"]["width"] * config["display"]["height"] * bytes_per_pixel
    rounded = (frame + 4095) // 4096 * 4096
    top = config["mem"]["size_mib"] << 20
    return top - 2 * rounded, top - rounded, frame, config["display"]["format"]


def same_outputs(out, reference, what):
    for frame in ("frame_0000.png", "frame_0001.png"):
        check(os.path.exists(os.path.join(out, frame)), f"{what}: {frame} was not written")
        if os.path.exists(os.path.join(out, frame)):
            check(
                open(os.path.join(out, frame), "rb").read() == open(os.path.join(reference, frame), "rb").read(),
                f"{what}: {frame} differs from the run without GDB",
            )
    stats = json.load(open(os.path.join(out, "stats.json")))
    check(stats["exit_status"] == 0, f"{what}: stats.json's exit_status is {stats['exit_status']}")
    check(
        stats["stats"] == json.load(open(os.path.join(reference, "stats.json")))["stats"],
        f"{what}: the SoC's statistics differ from the run without GDB",
    )


def register(output, name):
    match = re.search(rf"^{name}\s+0x([0-9a-f]+)", output, re.M)
    return int(match.group(1), 16) if match else None


def main():
    soc_sim, apps_elf, fault_elf, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    for entry in os.listdir(work):
        subprocess.run(["rm", "-rf", os.path.join(work, entry)])
    scene = ["--set", "host.model=iss", "--app", "triangle", "--frames", "2"]
    present = "tessera::DisplayDriver::present()"

    # Bad input first: --gdb where no ISS runs.
    native = run([soc_sim, "--app", "triangle", "--gdb", "0", "--out", os.path.join(work, "native")])
    check(native.returncode == 2, f"--gdb with host.model=native exits {native.returncode}, not 2")
    check(
        "--gdb" in native.stderr and "host.model=native" in native.stderr,
        "--gdb with host.model=native: the error names neither: " + native.stderr.strip(),
    )

    reference = os.path.join(work, "plain")
    # Not quiet, as the runs under GDB (whose warnings are looked at): the
    # log level is in the configuration the program reads.
    plain = run([soc_sim, *scene, "--out", reference])
    if not check(plain.returncode == 0, f"the run without GDB exits {plain.returncode}: {plain.stderr}"):
        return 1
    fb0, fb1, frame_bytes, pixel_format = frame_buffers(soc_sim, scene)

    # A port in use, and a client that goes away without a word.
    waiting = Server(soc_sim, os.path.join(work, "gone"), scene)
    if check(waiting.port is not None, "soc_sim never listened"):
        check(
            f"waiting for GDB on 127.0.0.1:{waiting.port}" in open(waiting.out + ".stderr").read(),
            "soc_sim does not say where it waits for GDB",
        )
        taken = run([soc_sim, *scene, "--out", os.path.join(work, "taken"), "--gdb", str(waiting.port)])
        check(taken.returncode == 2, f"a port in use: soc_sim exits {taken.returncode}, not 2")
        check(
            f"cannot listen on 127.0.0.1:{waiting.port}" in taken.stderr,
            "a port in use: the error does not name the port: " + taken.stderr.strip(),
        )
        with socket.create_connection(("127.0.0.1", waiting.port), timeout=TIMEOUT_S) as client:
            client.sendall(b"$?#3f")
            reply = b""
            while not reply.endswith(b"#b8") and len(reply) < 64:
                reply += client.recv(64)
            check(reply == b"+$S05#b8", f"'?' before the first instruction: {reply!r}, not a SIGTRAP stop")
    status, stderr = waiting.finish()
    check(status == 0, f"GDB gone away: soc_sim exits {status}: {stderr}")
    check(
        "GDB went away without detaching; the program runs on" in stderr,
        "GDB gone away: soc_sim does not say so: " + stderr.strip(),
    )
    same_outputs(waiting.out, reference, "GDB gone away")

    # The session.
    server = Server(soc_sim, os.path.join(work, "session"), scene)
    if check(server.port is not None, "soc_sim never listened"):
        dump = os.path.join(work, "frame_buffer_0.bin")
        log = gdb(
            apps_elf,
            server.port,
            [
                f"break *'{present}'",
                "continue",
                "info registers",
                "x/3xw $r0",
                "set $r12 = 0x12345678",
                "print/x $r12",
                "set {unsigned int}($sp - 64) = 0x5a5aa5a5",
                "x/xw $sp - 64",
                f"dump binary memory {dump} {fb0} {fb0 + frame_bytes}",
                "stepi",
                "stepi",
                "info symbol $pc",
                "delete",
                "continue",
            ],
        )
        check(f"Breakpoint 1, {present.replace('()', '')}" in log, "no stop at the breakpoint on " + present)
        check(
            re.search(r"^pc\s+0x[0-9a-f]+\s+0x[0-9a-f]+ <" + re.escape(present) + ">$", log, re.M),
            "the PC is not at the start of " + present,
        )
        sp = register(log, "sp")
        check(
            sp is not None and 0x400000 - 0x40000 <= sp < 0x400000,
            f"SP {sp} is not in the program's stacks (256 KiB below 4 MiB, sw_driver/runtime/README.md)",
        )
        cpsr = register(log, "cpsr")
        check(cpsr is not None and cpsr & 0x3F == 0x13, f"CPSR {cpsr}: not supervisor mode in ARM state")
        words = re.search(r"^0x[0-9a-f]+:\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)$", log, re.M)
        check(
            words and (int(words.group(2), 16), int(words.group(3), 16)) == (fb0, fb1),
            f"the display driver's frame buffers (memory at r0) are not {fb0:#x} and {fb1:#x}",
        )
        check(re.search(r"^\$\d+ = 0x12345678$", log, re.M), "r12 does not read back what GDB wrote")
        check(re.search(r":\s+0x5a5aa5a5$", log, re.M), "the stack word does not read back what GDB wrote")
        if check(os.path.exists(dump), "GDB could not dump the frame buffer") and pixel_format == "rgb565":
            check(
                open(dump, "rb").read() == rgb565_of_png(os.path.join(reference, "frame_0000.png")),
                "the first frame buffer as GDB reads it is not the first frame shown",
            )
        check(present + " + 8 in section" in log, "two stepi did not move the PC by two instructions")
        check("exited normally" in log, "the program did not run to its exit under GDB")
        status, stderr = server.finish()
        check(status == 0, f"soc_sim under GDB exits {status}: {stderr}")
        same_outputs(server.out, reference, "under GDB")
        pc = register(log, "pc")

        # GDB kills the program at the breakpoint.
        killed = Server(soc_sim, os.path.join(work, "killed"), scene)
        if check(killed.port is not None, "soc_sim never listened"):
            gdb(apps_elf, killed.port, [f"break *'{present}'", "continue", "kill"])
            status, stderr = killed.finish()
            check(status == 1, f"killed by GDB: soc_sim exits {status}, not 1")
            check(
                pc is not None and f"killed by GDB at pc {pc:#010x}" in stderr,
                "killed by GDB: the error does not name the PC: " + stderr.strip(),
            )

    # A fault under GDB: shown as a stop, then the launcher's error.
    faulting = Server(soc_sim, os.path.join(work, "fault"), ["--app", fault_elf, "--no-frames"])
    if check(faulting.port is not None, "soc_sim never listened"):
        log = gdb(fault_elf, faulting.port, ["continue", "print/x $pc", "continue"])
        check("Program received signal SIGILL" in log, "the undefined instruction is not a SIGILL stop")
        check(re.search(r"^\$\d+ = 0x60$", log, re.M), "the stop is not at the undefined instruction (0x60)")
        check("Program terminated with signal SIGILL" in log, "continuing from the fault does not end the program")
        status, stderr = faulting.finish()
        check(status == 1, f"a fault under GDB: soc_sim exits {status}, not 1")
        check(
            "fault_1.elf: undefined instruction at pc 0x00000060" in stderr,
            "a fault under GDB: the launcher's error is missing: " + stderr.strip(),
        )

    print("PASSED" if not failures else f"{len(failures)} check(s) FAILED")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
