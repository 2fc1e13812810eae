#!/usr/bin/env python3
"""Mutation fuzzer for the plan and scenario readers, through the real `isg` binary.

Each case takes a reference plan or scenario, mutates it (structure-aware: a value replaced by an
extreme number, a control character, a wrong type; a field deleted; an array element duplicated
or dropped; or plain byte damage) and runs `isg check` and `isg world -o OUT` on it. It fails
when any run
  - crashes (killed by a signal), takes longer than the time limit, or exits with a code other
    than 0 (accepted) or 1 (bad input, with an "error:" line on stderr);
  - leaves a file behind after failing (the output path, or anything else in the work folder);
  - is accepted by `isg check` but rejected by `isg world` (or the other way round): whatever
    check accepts, world builds.
Usage: mutation_fuzz.py --isg build/cli/isg --plans worlds/plans --count 10000 --seed 1 -j 2
"""

import argparse
import concurrent.futures
import copy
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

EXTREME_NUMBERS = [0, -0.0, 1e-300, -1e-300, 1e-7, 1e-4, 0.001, 0.5, -1, -0.5, 3, 1e4, 10001,
                   -1e4, 1e6, -1e6, 1e300, -1e300, 1.7976931348623157e308, 2**53 + 1, 2**64,
                   -2**63, 123456789012]
STRANGE_STRINGS = ["", "\u0000", "a\u0000b", "W1\n", "--", "a--b", "<&>\"'", "x" * 5000,
                   "outside", "W1", "R1", "D1", "L0", "\u00e9\u4e2d", "\u007f", "../d1.json",
                   "/dev/zero", "d1.json", "tour"]


def all_paths(value, path=()):
    """Every (path, value) of a JSON document, the root included."""
    yield path, value
    if isinstance(value, dict):
        for key, child in value.items():
            yield from all_paths(child, path + (key,))
    elif isinstance(value, list):
        for index, child in enumerate(value):
            yield from all_paths(child, path + (index,))


def get(document, path):
    for token in path:
        document = document[token]
    return document


def put(document, path, value):
    if not path:
        return value
    get(document, path[:-1])[path[-1]] = value
    return document


def random_value(rng):
    kind = rng.randrange(8)
    if kind < 3:
        return rng.choice(EXTREME_NUMBERS)
    if kind < 5:
        return rng.choice(STRANGE_STRINGS)
    if kind == 5:
        return rng.choice([None, True, [], {}, [1e6, -1e6], [0, 0], [1, 2, 3]])
    if kind == 6:
        return [[rng.uniform(-1e3, 1e3), rng.uniform(-1e3, 1e3)] for _ in range(rng.randrange(1, 6))]
    return rng.uniform(-50, 50)


def mutate_structure(document, rng):
    document = copy.deepcopy(document)
    for _ in range(rng.choice([1, 1, 1, 2, 3, 5])):
        paths = list(all_paths(document))
        path, value = rng.choice(paths)
        numbers = [(p, v) for p, v in paths
                   if isinstance(v, (int, float)) and not isinstance(v, bool)]
        if numbers and rng.random() < 0.4:
            # Type-preserving: a number scaled or shifted, so that many cases still parse and
            # reach the world builder.
            path, value = rng.choice(numbers)
            new = rng.choice([value * rng.choice([0.5, 0.99, 1.01, 1.5, 2, 10, 100, 1e-3, -1]),
                              value + rng.choice([-10, -1, -0.1, 0.1, 1, 10, 1e-9, 1e3])])
            document = put(document, path, new)
            continue
        op = rng.randrange(10)
        if op < 4 or not path:
            if isinstance(value, (int, float)) and not isinstance(value, bool) and rng.random() < 0.5:
                new = value * rng.choice([0, -1, 1e-300, 1e6, 1e300, 1 + 1e-12, 1000, 2])
            else:
                new = random_value(rng)
            document = put(document, path, new)
        elif op < 6:
            parent = get(document, path[:-1])
            del parent[path[-1]]
        elif op < 8 and isinstance(value, list) and value:
            index = rng.randrange(len(value))
            if rng.random() < 0.5:
                value.insert(index, copy.deepcopy(value[index]))
            elif len(value) > 1:
                del value[index]
            else:
                value.extend(copy.deepcopy(value) * rng.choice([1, 10, 100]))
        elif op == 8 and isinstance(value, dict):
            value[rng.choice(["extra", "id", "name", "rooms", "plan"])] = random_value(rng)
        else:
            document = put(document, path, random_value(rng))
    return json.dumps(document, ensure_ascii=rng.random() < 0.5)


def mutate_bytes(text, rng):
    data = bytearray(text.encode())
    for _ in range(rng.randrange(1, 6)):
        op = rng.randrange(4)
        at = rng.randrange(len(data)) if data else 0
        if op == 0:
            del data[at:]
        elif op == 1 and data:
            data[at] = rng.randrange(256)
        elif op == 2:
            data[at:at] = rng.choice([b"\x00", b",", b"]", b"}", b"1e999", b'"', b"\\u0000", b"-"])
        elif data:
            del data[at:at + rng.randrange(1, 20)]
    return bytes(data)


def run(isg, args, cwd, timeout):
    started = time.monotonic()
    try:
        done = subprocess.run([isg] + args, cwd=cwd, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "", time.monotonic() - started
    return done.returncode, done.stderr.decode(errors="replace"), time.monotonic() - started


def check_case(isg, seeds, index, seed, timeout):
    rng = random.Random(seed * 1_000_003 + index)
    name, text = rng.choice(seeds)
    if rng.random() < 0.8:
        payload = mutate_structure(json.loads(text), rng).encode()
    else:
        payload = mutate_bytes(text, rng)
    problems = []
    work = tempfile.mkdtemp(prefix="isg-fuzz-")
    try:
        # Scenarios name their plan by file: give them the reference plans next to them.
        for plan_name, plan_text in seeds:
            if not plan_name.endswith(".asbuilt.json"):
                with open(os.path.join(work, plan_name), "w") as out:
                    out.write(plan_text)
        case = os.path.join(work, "case.json")
        with open(case, "wb") as out:
            out.write(payload)
        before = set(os.listdir(work))
        codes = {}
        for command, args in (("check", ["check", "case.json"]),
                              ("world", ["world", "case.json", "-o", "out/world.xml"])):
            os.makedirs(os.path.join(work, "out"), exist_ok=True)
            code, err, seconds = run(isg, args, work, timeout)
            codes[command] = code
            if code is None:
                problems.append(f"{command}: hang (> {timeout} s)")
            elif code < 0:
                problems.append(f"{command}: killed by signal {-code}: {err.strip()[:200]}")
            elif code not in (0, 1):
                problems.append(f"{command}: exit {code}: {err.strip()[:300]}")
            elif code == 1 and "error:" not in err:
                problems.append(f"{command}: exit 1 without an error message")
            if command == "world":
                written = os.listdir(os.path.join(work, "out"))
                if code != 0 and written:
                    problems.append(f"world: failed but left {written}")
                shutil.rmtree(os.path.join(work, "out"))
        after = set(os.listdir(work)) - {"out"}
        if after != before:
            problems.append(f"left files behind: {sorted(after - before)}")
        if codes["check"] in (0, 1) and codes["world"] in (0, 1) and codes["check"] != codes["world"]:
            problems.append(f"check exits {codes['check']} but world exits {codes['world']}")
        return {"index": index, "seed_file": name, "codes": codes, "problems": problems,
                "payload": payload if problems else None}
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--isg", required=True, help="the isg binary")
    parser.add_argument("--plans", required=True, help="folder of reference plans and scenarios")
    parser.add_argument("--count", type=int, default=1000, help="mutated files to try")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds per command")
    parser.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--keep", help="folder to keep failing inputs in")
    args = parser.parse_args()

    isg = os.path.abspath(args.isg)
    seeds = []
    for name in sorted(os.listdir(args.plans)):
        if name.endswith(".json"):
            with open(os.path.join(args.plans, name)) as f:
                seeds.append((name, f.read()))
    if not seeds:
        sys.exit(f"{args.plans}: no .json files to mutate")

    counts = {"accepted": 0, "rejected": 0}
    failures = []
    started = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(check_case, isg, seeds, i, args.seed, args.timeout)
                   for i in range(args.count)]
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            result = future.result()
            counts["accepted" if result["codes"]["check"] == 0 else "rejected"] += 1
            if result["problems"]:
                failures.append(result)
                print(f"case {result['index']} (from {result['seed_file']}): "
                      + "; ".join(result["problems"]), file=sys.stderr)
            if done % 500 == 0:
                print(f"{done}/{args.count} cases, {len(failures)} failing, "
                      f"{time.monotonic() - started:.0f} s", file=sys.stderr)
    if args.keep and failures:
        os.makedirs(args.keep, exist_ok=True)
        for f in failures:
            with open(os.path.join(args.keep, f"case{f['index']}.json"), "wb") as out:
                out.write(f["payload"])
    print(f"{args.count} mutated plans and scenarios (seed {args.seed}): "
          f"{counts['accepted']} accepted, {counts['rejected']} rejected with exit 1, "
          f"{len(failures)} failing, {time.monotonic() - started:.0f} s")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
