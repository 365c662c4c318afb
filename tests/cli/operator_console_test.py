#!/usr/bin/env python3
"""The run's terminal as an operator meets it, on a real pseudo-terminal.

usage: operator_console_test.py CELLCTL CONFIG RECIPE RUN_DIR

Runs RECIPE with --emulate under a pty, types HOLD (capitals), an unknown word, unhold, then
Ctrl-C (the default cell holds), unhold (refused: the stop is latched), reset, unhold, and finally
`s`. Checks that every line typed is answered, that the Ctrl-C hold says what to type next, that
typing never lands on the status line, that a typed stop exits 130 like Ctrl-C, and that the
journal holds the commands and the unknown word. Waits on what the screen says, never on fixed
sleeps alone: each step waits (up to 20 s) for the answer to the one before.
"""
import json
import os
import pty
import re
import select
import sys
import time

cellctl, config, recipe, run_dir = sys.argv[1:5]
pid, fd = pty.fork()
if pid == 0:
    os.environ["TERM"] = "xterm"
    os.execv(cellctl, [cellctl, "run", recipe, "--emulate", "--journal", run_dir, "-c", config])

raw = b""


def screen():
    text = re.sub(r"\x1b\[[0-9;]*[A-Za-z]", "", raw.decode(errors="replace"))
    lines = []
    for chunk in text.split("\n"):
        segs = [s for s in chunk.split("\r") if s.strip()]
        lines.append(segs[-1] if segs else "")
    return "\n".join(lines)


def wait_for(pattern, timeout=20.0):
    global raw
    end = time.time() + timeout
    while time.time() < end:
        if re.search(pattern, screen()):
            return
        r, _, _ = select.select([fd], [], [], 0.05)
        if r:
            try:
                raw += os.read(fd, 65536)
            except OSError:
                break
    print(screen())
    sys.exit(f"FAIL: no '{pattern}' on the screen within {timeout} s")


wait_for(r"step 2/6 go")  # the status line: the first move is under way
# A move's planned time is known once it starts (its profile): elapsed of planned on the status line.
wait_for(r"step 2/6 go[^\n]* · [0-9]+\.[0-9] of [0-9]+\.[0-9] s")
os.write(fd, b"HOLD\n")
wait_for(r"hold: accepted")
wait_for(r"Holding → Held")
os.write(fd, b"foo\n")
wait_for(r"'foo' is not a command: type hold, unhold, stop, abort, reset or clear")
os.write(fd, b"unhold\n")
wait_for(r"Held → Unholding")
os.write(fd, b"\x03")  # Ctrl-C through the terminal's line discipline: SIGINT
wait_for(r"Ctrl-C: the cell holds — type `stop` to end, or `reset` then `unhold` to go on")
wait_for(r"(?s)Ctrl-C: the cell holds.*→ Held")
os.write(fd, b"unhold\n")
wait_for(r"unhold: received — checking the latched faults")
wait_for(r"refused: unhold refused: a latched fault still demands a stop \(reset it first\) — type reset, then unhold")
os.write(fd, b"reset\n")
wait_for(r"reset: done, faults cleared — type unhold to go on, or stop to end")
os.write(fd, b"unhold\n")
wait_for(r"(?s)reset: done.*Unholding → Execute")
os.write(fd, b"s\n")
wait_for(r"> s: taken as 'stop'")
while True:  # everything cellctl wrote, to its end
    try:
        chunk = os.read(fd, 65536)
    except OSError:
        break
    if not chunk:
        break
    raw += chunk
_, status = os.waitpid(pid, 0)
code = os.waitstatus_to_exitcode(status)
text = screen()
print(text)
failures = []
if code != 130:
    failures.append(f"a typed stop exited {code}, expected 130 (as Ctrl-C)")
for line in text.splitlines():
    # Typed text must never be glued onto the status line.
    if re.search(r"mm \| spindle .*(HOLD|foo|unhold)", line):
        failures.append(f"typing glued onto the status line: {line!r}")
if "(interrupted by the stop)" not in text:
    failures.append("the summary leaves out the step the stop interrupted")
events = [json.loads(l) for l in open(os.path.join(run_dir, "journal.jsonl"))]
commands = [(e["command"], e["source"]) for e in events if e["event"] == "command"]
notes = [e["text"] for e in events if e["event"] == "note"]
for wanted in [("hold", "terminal"), ("unhold", "terminal"), ("stop", "terminal")]:  # who commanded
    if wanted not in commands:
        failures.append(f"journal lacks command {wanted}: {commands}")
if not any("operator typed 'foo'" in n for n in notes):
    failures.append(f"journal lacks the unknown word: {notes}")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
