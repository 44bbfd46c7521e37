#!/usr/bin/env bash
# Interrupts (docs/exit-codes.md "Interrupted"): SIGINT or SIGTERM while a tool writes its output
# removes the temporary `.NAME.tmp-PID.ext` (it was left behind: meshconvert -o x.msh / x.vtu,
# dgsolve, lpcvt), leaves the old output as it was, and ends the tool by that signal (a shell's
# status 130 / 143). meshplot -o PIC.png signalled while rsvg-convert renders kills rsvg-convert
# and removes the PNG's temporary and the SVG it read (SIGINT was ignored during std::system's
# shell, SIGTERM left rsvg-convert running and both temporaries behind). bamgquad signalled alone
# while ffbamg runs kills ffbamg and removes its /tmp/quadapt-ffbamg-XXXXXX directory (both were
# left behind).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
mkdir tmp
export TMPDIR=$T/tmp

# a mesh whose writing takes long enough to be caught: 300 x 300 quads (9 MB)
python3 "$S/tests/golden/refine/make_square.py" 300 big.msh
meshconvert -q big.msh -o out.msh
meshconvert -q big.msh -o out.vtu
sha256sum out.msh out.vtu > before.sha

# interrupt.py SIG WHAT CMD...: runs CMD, sends SIG to it (only to it) as soon as WHAT exists
# ("tmp": a temporary beside the output; "child": a child process; "child:NAME": a child or
# grandchild whose command line contains NAME), and prints "rc=R caught=1 child=PID" (R < 0: ended
# by signal -R; caught=0: the moment never came).
cat > interrupt.py <<'PY'
import glob, os, signal, subprocess, sys, time
sig, what, cmd = getattr(signal, sys.argv[1]), sys.argv[2], sys.argv[3:]
p = subprocess.Popen(cmd, stderr=subprocess.DEVNULL)
caught, child = 0, 0
def children(pid):
    try:
        return [int(k) for k in open("/proc/%d/task/%d/children" % (pid, pid)).read().split()]
    except OSError:
        return []
def named(pid, name):
    try:
        return name.encode() in open("/proc/%d/cmdline" % pid, "rb").read()
    except OSError:
        return False
while p.poll() is None and not caught:
    if what == "tmp":
        caught = int(bool(glob.glob(".out.tmp-*")))
    elif what == "child":
        kids = children(p.pid)
        if kids:
            child, caught = kids[0], 1
    else:
        name = what.split(":", 1)[1]
        for k in children(p.pid) + [g for c in children(p.pid) for g in children(c)]:
            if named(k, name):
                child, caught = k, 1
                break
    if caught:
        p.send_signal(sig)
p.wait()
print("rc=%d caught=%d child=%d" % (p.returncode, caught, child))
PY
# interrupted SIG WHAT NAME CMD...: CMD (interrupt.py SIG WHAT) ended by SIG, and its child, whose
# command line names NAME, gone 0.2 s later
interrupted() {
  local sig=$1 what=$2 name=$3
  shift 3
  local num res child
  num=$(python3 -c "import signal; print(int(signal.$sig))")
  res=$(python3 interrupt.py "$sig" "$what" "$@")
  case "$res" in
    "rc=-$num caught=1 child="*) ;;
    *) fail "$1, $sig while $name runs: $res (want ended by signal $num)" ;;
  esac
  child=${res##*child=}
  # a killed child may take a moment to be reaped on a loaded machine: up to 5 s
  for _ in $(seq 50); do
    { [ -e "/proc/$child" ] && grep -q "$name" "/proc/$child/cmdline" 2>/dev/null; } || break
    sleep 0.1
  done
  if [ -e "/proc/$child" ] && grep -q "$name" "/proc/$child/cmdline" 2>/dev/null; then fail "$1, $sig: $name ($child) still runs"; fi
}

for sig in SIGINT SIGTERM; do
  num=$(python3 -c "import signal; print(int(signal.$sig))")
  for out in out.msh out.vtu; do
    res=$(python3 interrupt.py $sig tmp meshconvert -q big.msh -o $out)
    case "$res" in
      "rc=-$num caught=1 "*) ;;
      *) fail "meshconvert -o $out, $sig during the write: $res (want ended by signal $num)" ;;
    esac
    if compgen -G '.*.tmp-*' > /dev/null; then fail "$sig left a temporary: $(ls -A)"; fi
    sha256sum -c --quiet before.sha || fail "$sig changed the old output"
  done
done
# the status a shell sees (SIGTERM: a background job of a script ignores SIGINT)
rc=0
meshconvert -q big.msh -o out.msh &
p=$!
while kill -0 $p 2>/dev/null && ! compgen -G '.out.tmp-*' > /dev/null; do :; done
kill -TERM $p
wait $p || rc=$?
[ $rc -eq 143 ] || fail "SIGTERM during the write: status $rc (want 143)"
if compgen -G '.*.tmp-*' > /dev/null; then fail "SIGTERM left a temporary: $(ls -A)"; fi

# meshplot -o PIC.png: SIGTERM / SIGINT to meshplot alone while rsvg-convert runs (the 300 x 300
# mesh: ~0.9 s of rendering), caught as the child (or grandchild, through a shell) whose command
# line names the picture's temporaries
# running PATTERN: the processes (but this one) whose command line contains PATTERN
running() {
  python3 - "$1" <<'PY'
import os, sys
for p in os.listdir("/proc"):
    if p.isdigit() and int(p) != os.getpid():
        try:
            cmd = open(f"/proc/{p}/cmdline", "rb").read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if sys.argv[1] in cmd:
            print(p, cmd)
PY
}
if command -v rsvg-convert > /dev/null; then
  for sig in SIGTERM SIGINT; do
    interrupted $sig child:.pic.tmp- rsvg-convert meshplot -q big.msh -o pic.png
    for _ in $(seq 50); do [ -z "$(running ".pic.tmp-")" ] && break; sleep 0.1; done
    left=$(running ".pic.tmp-")
    [ -z "$left" ] || fail "$sig: still running on meshplot's temporaries: $left"
    if compgen -G '.pic.*' > /dev/null || [ -e pic.png ] || [ -e pic.png.json ]; then fail "$sig: left behind: $(ls -A)"; fi
    if [ -n "$(ls -A tmp)" ]; then fail "$sig: left in TMPDIR: $(ls -A tmp)"; fi
  done
  meshplot -q big.msh -o pic.png  # and uninterrupted, the picture
  [ "$(head -c 4 pic.png | tail -c 3)" = PNG ] || fail "meshplot -o pic.png wrote no PNG"
  rm pic.png pic.png.json
else
  echo "note: rsvg-convert not installed: meshplot's interrupt during the PNG rendering not tried"
fi

# bamgquad: SIGTERM / SIGINT to bamgquad alone while ffbamg runs
if ! command -v ffbamg > /dev/null && [ -z "${QUADAPT_FFBAMG:-}" ]; then
  echo "ok: interrupts remove temporaries (ffbamg not installed: bamgquad not tried)"
  exit 0
fi
cp "$E/meshes/square16.msh" m.msh
dgsolve -q m.msh -c "$E/cases/smooth.json" -p 1 -o sol.msh
estimate-frame -q sol.msh -o shape.msh
size-solve -q shape.msh --complexity 20000 -o frame.msh
for sig in SIGTERM SIGINT; do
  interrupted $sig child ffbamg bamgquad -q frame.msh -o bq.msh --runs 1
  if [ -n "$(ls -A tmp)" ]; then fail "$sig: left in TMPDIR: $(ls -A tmp)"; fi
  if [ -e bq.msh ] || compgen -G '.*.tmp-*' > /dev/null; then fail "$sig: an output was written"; fi
done
echo "ok: interrupts remove temporaries, ffbamg and its directory"
