#!/usr/bin/env python3
"""How honest is the progress line's "~N s left"? Runs one `packbed generate` on a
pseudo-terminal 150 columns wide (as a user's terminal), stamps every progress line with the
time it arrived, and prints, once a second of the run, what the line said was left against
what was left: for a run in layers the whole run (the time to the end of the relaxation,
`seconds` in summary.json), in one piece the stage being relaxed. The largest error from the
third second on is the figure quoted in docs/performance.md ("Time left").

Usage: bench/time_left.py [--packbed build/packbed] [GENERATE OPTIONS ...]
  default options: -a 20 -n 60000 -s 1 (6 layers)
"""
import fcntl
import json
import os
import pty
import re
import struct
import sys
import tempfile
import termios
import time


def main():
    argv = sys.argv[1:]
    exe = "build/packbed"
    if argv[:1] == ["--packbed"]:
        exe, argv = argv[1], argv[2:]
    options = argv or ["-a", "20", "-n", "60000", "-s", "1"]
    out = tempfile.mkdtemp(prefix="packbed-time-left.")
    pid, fd = pty.fork()
    if pid == 0:
        os.execvp(exe, [exe, "generate", *options, "--force", "-o", out])
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 150, 0, 0))
    start = time.monotonic()
    stamped, text = [], b""
    while True:
        try:
            chunk = os.read(fd, 65536)
        except OSError:
            break
        if not chunk:
            break
        now = time.monotonic() - start
        text += chunk
        *lines, text = re.split(rb"[\r\n]", text)
        stamped += [(now, line.decode("utf-8", "replace")) for line in lines]
    _, status = os.waitpid(pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"time_left.py: packbed exited with {os.waitstatus_to_exitcode(status)}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    layered = summary.get("layers", 1) > 1
    # The stage a line speaks of: its first word after the counters ("initial", ...).
    said = []  # (t, seconds left said, stage or None)
    for t, line in stamped:
        m = re.search(r"~(\d+) s left", line)
        if m:
            stage = re.search(r"\b(initial|intermediate|final)\b", line)
            said.append((t, float(m.group(1)), stage.group(1) if stage else None))
    if not said:
        sys.exit("time_left.py: no \"s left\" on the progress line")
    # The end of what was estimated: the run's relaxation, or each stage's last line.
    stage_end = {}
    for t, _, stage in said:
        stage_end[stage] = t
    relax_end = max(t for t, _, _ in said)
    print(f"packbed generate {' '.join(options)}: {summary['seconds']:.1f} s relaxation, "
          f"{'layers' if layered else 'one piece'}")
    print("| at (s) | said left (s) | was left (s) |")
    print("|---|---|---|")
    worst, worst_all, shown = 0.0, 0.0, -1
    for t, left, stage in said:
        end = relax_end if layered else stage_end[stage]
        error = abs(left - (end - t))
        worst_all = max(worst_all, error)
        if t >= 3:
            worst = max(worst, error)
        if int(t) > shown:
            shown = int(t)
            print(f"| {t:.1f} | {left:.0f} | {end - t:.1f} |")
    print(f"\nlargest error: {worst:.1f} s from the third second on, {worst_all:.1f} s in all")


if __name__ == "__main__":
    main()
