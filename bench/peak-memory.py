#!/usr/bin/env python3
"""Runs a command and prints its wall time and the peak of the resident memory of its whole
process tree, summed (a forked reader and its parent together, as the machine sees them),
sampled every 20 ms from /proc: "SECONDS KIB". With --until-converged STATE.json the command
(`cloudvis view ... --state-file STATE.json`) is ended once that state says converged.

Usage: peak-memory.py [--until-converged STATE.json] COMMAND [ARGUMENTS...]"""
import json
import os
import signal
import subprocess
import sys
import time

arguments = sys.argv[1:]
state = None
if arguments[:1] == ["--until-converged"]:
    state, arguments = arguments[1], arguments[2:]


def tree_rss_kib(root):
    """The summed VmRSS of `root` and its descendants."""
    children = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/stat" % entry) as stat:
                    parent = int(stat.read().rsplit(")", 1)[1].split()[1])
                children.setdefault(parent, []).append(int(entry))
            except (OSError, ValueError, IndexError):
                pass
    total, pending = 0, [root]
    while pending:
        pid = pending.pop()
        pending.extend(children.get(pid, []))
        try:
            with open("/proc/%d/status" % pid) as status:
                for line in status:
                    if line.startswith("VmRSS:"):
                        total += int(line.split()[1])
        except OSError:
            pass
    return total


def converged():
    try:
        with open(state) as f:
            return bool(json.load(f).get("converged"))
    except (OSError, ValueError):
        return False


start = time.monotonic()
process = subprocess.Popen(arguments, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
peak = 0
while process.poll() is None:
    peak = max(peak, tree_rss_kib(process.pid))
    if state and converged():
        process.send_signal(signal.SIGTERM)
        break
    time.sleep(0.02)
seconds = time.monotonic() - start
error = process.communicate()[1]
if not state and process.returncode != 0:
    sys.stderr.write(error.decode(errors="replace"))
    sys.exit(1)
print("%.2f %d" % (seconds, peak))
