#!/usr/bin/env bash
# GDB (gdb-multiarch, batch mode) against iss_run --gdb: a breakpoint at a
# function, registers and memory read back, single steps, a breakpoint
# removed, the program run to its exit.
#   gdb_session.sh ISS_RUN PROGRAM.elf WORK_DIR
set -uo pipefail
iss_run=$1 elf=$2 work=$3
mkdir -p "$work"
rm -f "$work/port" "$work/gdb.log"
"$iss_run" "$elf" --gdb 0 --gdb-port-file "$work/port" > "$work/console.txt" 2> "$work/iss_run.log" &
server=$!
trap 'kill $server 2> /dev/null || true' EXIT
for _ in $(seq 100); do [[ -s "$work/port" ]] && break; sleep 0.1; done
[[ -s "$work/port" ]] || { echo "iss_run never listened"; cat "$work/iss_run.log"; exit 1; }
port=$(cat "$work/port")
gdb-multiarch -nx -batch "$elf" \
  -ex "set pagination off" \
  -ex "target remote 127.0.0.1:$port" \
  -ex "break put_hex" \
  -ex "continue" \
  -ex "info registers pc" \
  -ex "print/x \$r1" \
  -ex "x/s \$r0" \
  -ex "x/2xw &seed" \
  -ex "stepi" \
  -ex "stepi" \
  -ex "info registers pc" \
  -ex "delete" \
  -ex "continue" > "$work/gdb.log" 2>&1
status=$?
wait $server
server_status=$?
trap - EXIT
cat "$work/gdb.log"
echo "gdb exit $status, iss_run exit $server_status"
fail() { echo "FAILED: $1"; exit 1; }
[[ $status -eq 0 ]] || fail "gdb exited $status"
[[ $server_status -eq 0 ]] || fail "iss_run exited $server_status"
# put_hex("sum", sum) is the first call: the native build prints "sum f3c3f0b0"
grep -q "Breakpoint 1, 0x[0-9a-f]* in put_hex" "$work/gdb.log" || fail "no stop at the breakpoint on put_hex"
grep -Eq '^\$[0-9]+ = 0x'"$(awk '/^sum /{print $2}' "$work/console.txt" | sed 's/^0*//')"'$' "$work/gdb.log" ||
  fail "r1 (put_hex's value) is not the sum the program prints"
grep -Eq ':[[:space:]]+"sum"$' "$work/gdb.log" || fail "r0 does not point at the label \"sum\""
grep -Eq "^pc +0x[0-9a-f]+ +0x[0-9a-f]+ <put_hex\+8>" "$work/gdb.log" || fail "two stepi did not move the pc by two instructions"
grep -q "exited normally" "$work/gdb.log" || fail "the program did not run to its exit"
grep -q "crc32 " "$work/console.txt" || fail "the program's output is missing"
echo "PASSED"
