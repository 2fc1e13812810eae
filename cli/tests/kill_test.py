#!/usr/bin/env python3
"""Kill tests: `isg simulate`, `isg run` and `isg generate` are killed at random moments
(SIGKILL, SIGTERM or SIGINT, from a seeded generator), and the output path must never hold a
partial dataset, run or buildings folder: either nothing, or the complete folder. After SIGTERM and SIGINT the process's own
temporary folder may not remain either; after SIGKILL the next complete run to the same path must
remove the one left behind.
Usage: kill_test.py ISG_EXECUTABLE [--rounds 20] [--seed 1]
"""

import argparse
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

COMMANDS = {
    # name: (arguments before -o, the files a complete folder holds). Each takes 1.5-2 s here, so
    # that most kills land while the command works, not while the process is still loading.
    "simulate": (["simulate", "builtin:d3", "--duration", "40", "-q"],
                 ["metadata.json", "groundtruth.tum", "odometry.tum", "scans.tum", "scans"]),
    "run": (["run", "builtin:d3", "--duration", "100", "-q"],
            ["metrics.json", "estimate.tum", "groundtruth.tum", "report.svg"]),
    # Buildings are checked one by one before the folder is written: a signal during the last
    # one's check (the moment an earlier version deferred to the end and exited 0) must leave
    # nothing.
    "generate": (["generate", "office", "--count", "6", "--rooms", "30", "-q"],
                 [f"office-{k}{ext}" for k in range(1, 7) for ext in (".json", ".asbuilt.json")]
                 + [".isg-output"]),
}


def complete(command, path):
    """Whether `path` is a whole output folder of `command`."""
    _, files = COMMANDS[command]
    if not all(os.path.exists(os.path.join(path, f)) for f in files):
        return False
    if command == "simulate":
        with open(os.path.join(path, "scans.tum")) as f:
            stamps = sum(1 for line in f if line.strip() and not line.startswith("#"))
        return stamps == len(os.listdir(os.path.join(path, "scans"))) and stamps > 0
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("isg")
    parser.add_argument("--rounds", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    args.isg = os.path.abspath(args.isg)
    rng = random.Random(args.seed)
    problems = []
    work = tempfile.mkdtemp(prefix="isg-kill-")
    try:
        for command, (arguments, _) in COMMANDS.items():
            # How long a whole run takes here: the kill times are drawn over it.
            started = time.monotonic()
            subprocess.run([args.isg] + arguments + ["-o", "timing"], cwd=work, check=True,
                           capture_output=True)
            whole = time.monotonic() - started
            shutil.rmtree(os.path.join(work, "timing"))
            killed_by = {}
            for round_ in range(args.rounds):
                sig = rng.choice([signal.SIGKILL, signal.SIGKILL, signal.SIGTERM, signal.SIGINT])
                delay = rng.uniform(0.0, whole * 1.1)
                process = subprocess.Popen([args.isg] + arguments + ["--force", "-o", "out"],
                                           cwd=work, stdout=subprocess.DEVNULL,
                                           stderr=subprocess.PIPE)
                time.sleep(delay)
                process.send_signal(sig)
                _, err = process.communicate()
                code = process.returncode
                out = os.path.join(work, "out")
                what = f"{command} round {round_}: {signal.Signals(sig).name} after {delay:.2f} s"
                if os.path.exists(out) and not complete(command, out):
                    problems.append(f"{what}: partial folder at the output path")
                # Its own temporary folder (named with its pid) must be gone. Those of earlier
                # SIGKILLed rounds may remain until a run gets as far as writing (checked below):
                # a signal that arrives while the process is still loading kills it before it
                # does anything, cleaning included.
                own = f".out.partial{process.pid}"
                if sig != signal.SIGKILL and own in os.listdir(work):
                    problems.append(f"{what}: exit {code} left {own}: {err.decode()[:200]}")
                if sig != signal.SIGKILL and code not in (0, 128 + sig, -sig):
                    problems.append(f"{what}: exit {code}: {err.decode()[:200]}")
                killed_by[sig] = killed_by.get(sig, 0) + 1
            # The next complete run removes what the SIGKILLed ones left.
            subprocess.run([args.isg] + arguments + ["--force", "-o", "out"], cwd=work,
                           check=True, capture_output=True)
            leftovers = [n for n in os.listdir(work) if n.startswith(".out.partial")]
            if leftovers:
                problems.append(f"{command}: a complete run left {leftovers}")
            if not complete(command, os.path.join(work, "out")):
                problems.append(f"{command}: the complete run's folder is not complete")
            shutil.rmtree(os.path.join(work, "out"))
            print(f"{command}: {args.rounds} kills in [0, {whole * 1.1:.1f}] s ("
                  + ", ".join(f"{signal.Signals(s).name} {n}" for s, n in sorted(killed_by.items()))
                  + ")")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for p in problems:
        print(p, file=sys.stderr)
    print(f"{len(problems)} problems")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
