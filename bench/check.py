#!/usr/bin/env python3
"""make bench-check: the ratios that matter, on small sizes, against the figures last recorded.

Runs cloudvis-bench-rendering (both fields against VTK's mapper, the lighting models against
`none`) and cloudvis-bench-generation (against vtkSampleFunction) ROUNDS times each, keeps each
ratio's best round (timings on a shared machine only ever get worse by chance), and compares them
with bench/check-figures.json. Prints every ratio with its change, then each one that got worse
by more than 15%. A ratio is a time of cloudvis against its peer in the same run, so the figures
carry over between runs on one machine better than times do; across machines (llvmpipe against
a GPU) they do not: record on the machine you check on.

    make bench-check                       # compare (exit 1 when a ratio got worse by > 15%)
    python3 bench/check.py --record        # write the figures of this run as the new record

Never part of ctest or CI: timings on shared machines are noisy. Exit status: 0 nothing worse,
1 something worse, 2 a bench did not run or printed no ratio.
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
FIGURES = os.path.join(HERE, "check-figures.json")
WORSE_BY = 0.15  # a ratio worse by more than this fraction is reported

RENDERING = ["--size", "96", "--frames", "5", "--width", "400", "--height", "300"]
GENERATION = ["--size", "96", "--repeat", "3", "--cloudscape-size", "96", "--noise-size", "8"]

# name, the bench, the line's pattern (its first group the ratio), whether higher is better.
NUMBER = r"([0-9]+(?:\.[0-9]+)?)"
RATIOS = [
    ("sparse unlit vs VTK", "rendering", r"sparse speed-up ratio: " + NUMBER, True),
    ("dense unlit vs VTK", "rendering", r"dense speed-up ratio: " + NUMBER, True),
    ("derivative vs none", "rendering", r"^\s*derivative\s.*\(" + NUMBER + r" x none\)", False),
    ("march (multiple-scattering volume) vs none", "rendering",
     r"^\s*march \(light volumes, multiple-scattering volume\)\s.*\(" + NUMBER + r" x none\)",
     False),
    ("march (octaves) vs none", "rendering",
     r"^\s*march \(light volumes, octaves\)\s.*\(" + NUMBER + r" x none\)", False),
    ("march vs VTK shaded", "rendering",
     r"march \(light volumes\) vs VTK shaded speed-up ratio: " + NUMBER, True),
    ("generation vs vtkSampleFunction", "generation", r"generation speed-up ratio: " + NUMBER,
     True),
]


def run_bench(build, name, arguments, timeout):
    program = os.path.join(build, "bin", "cloudvis-bench-" + name)
    if not os.access(program, os.X_OK):
        sys.exit(f"bench-check: {program} is missing: build first (make build)")
    try:
        done = subprocess.run([program] + arguments, capture_output=True, text=True,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        print(f"bench-check: {program} ran past {timeout} s", file=sys.stderr)
        sys.exit(2)
    if done.returncode != 0:
        print(f"bench-check: {program} {' '.join(arguments)} exited with {done.returncode}:\n"
              f"{done.stderr}", file=sys.stderr)
        sys.exit(2)
    return done.stdout


def measure(build, rounds):
    best = {}
    for _ in range(rounds):
        outputs = {"rendering": run_bench(build, "rendering", RENDERING, 60),
                   "generation": run_bench(build, "generation", GENERATION, 30)}
        for name, bench, pattern, higher in RATIOS:
            found = re.search(pattern, outputs[bench], re.MULTILINE)
            if not found:
                print(f"bench-check: cloudvis-bench-{bench} printed no \"{name}\" "
                      f"(/{pattern}/):\n{outputs[bench]}", file=sys.stderr)
                sys.exit(2)
            value = float(found.group(1))
            if name not in best:
                best[name] = value
            else:
                best[name] = max(best[name], value) if higher else min(best[name], value)
    return best


def processor():
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.machine()


def write_atomically(path, text):
    folder = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(dir=folder, prefix=".check-figures.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w") as out:
            out.write(text)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build", help="the build folder (default: build)")
    parser.add_argument("--rounds", type=int, default=2,
                        help="runs of each bench; each ratio's best counts (default 2)")
    parser.add_argument("--figures", default=FIGURES,
                        help=f"the recorded figures (default: {os.path.relpath(FIGURES)})")
    parser.add_argument("--record", action="store_true",
                        help="write this run's ratios as the recorded figures")
    options = parser.parse_args()
    if options.rounds < 1:
        parser.error("--rounds must be at least 1")

    started = time.monotonic()
    now = measure(options.build, options.rounds)
    seconds = time.monotonic() - started
    higher = {name: better for name, _, _, better in RATIOS}

    if options.record:
        record = {
            "recorded": datetime.date.today().isoformat(),
            "machine": f"{processor()}, {os.cpu_count()} cores",
            "command": "python3 bench/check.py --record (make bench-check compares)",
            "rendering": " ".join(RENDERING),
            "generation": " ".join(GENERATION),
            "rounds": options.rounds,
            "ratios": {name: now[name] for name, _, _, _ in RATIOS},
        }
        write_atomically(options.figures, json.dumps(record, indent=2) + "\n")
        for name, value in now.items():
            print(f"  {name:45s} {value:6.2f}")
        print(f"recorded in {os.path.relpath(options.figures)} ({seconds:.0f} s)")
        return 0

    try:
        with open(options.figures) as figures:
            record = json.load(figures)
        recorded = record["ratios"]
    except (OSError, ValueError, KeyError) as problem:
        print(f"bench-check: {options.figures}: cannot read the recorded figures ({problem}); "
              f"write them with python3 bench/check.py --record", file=sys.stderr)
        return 2
    print(f"bench-check: best of {options.rounds} rounds against the figures of "
          f"{record.get('recorded', '?')} ({record.get('machine', '?')}):")
    worse = []
    for name, _, _, better in RATIOS:
        value = now[name]
        then = recorded.get(name)
        if then is None:
            print(f"  {name:45s} {value:6.2f}  (not recorded)")
            continue
        # How much worse, as a fraction: a lower speed-up, or a higher cost against `none`.
        loss = (then / value - 1.0) if better else (value / then - 1.0)
        word = "worse" if loss > 0 else "better"
        print(f"  {name:45s} {value:6.2f}  recorded {then:6.2f}  {abs(loss) * 100:5.1f}% {word}"
              f"  ({'higher' if higher[name] else 'lower'} is better)")
        if loss > WORSE_BY:
            worse.append((name, value, then, loss))
    print(f"({seconds:.0f} s)")
    if worse:
        print(f"worse by more than {WORSE_BY * 100:.0f}%:")
        for name, value, then, loss in worse:
            print(f"  {name}: {value:.2f} against {then:.2f} recorded ({loss * 100:.0f}% worse)")
        return 1
    print(f"no ratio worse by more than {WORSE_BY * 100:.0f}%")
    return 0


if __name__ == "__main__":
    sys.exit(main())
