#!/usr/bin/env python3
"""Stress suite of the iS-Graph localizer (docs/slam.md, "Never wrong under drift").

Writes scenarios that degrade a reference world (D1–D6 as built) with odometry heading bias,
LiDAR dropout, clutter boxes and a closed door, runs `isg run` on each, and prints a summary: how
many runs localized, how many were wrongly localized (metrics.json `wrongly_localized`), and the
S-Graph's APE in M against the odometry's per heading-bias level. Every scenario is drawn from the
suite seed, so the suite is the same every time it is run.

  slam/isgraph/stress/stress_suite.py --isg build/cli/isg --out /tmp/stress [--worlds d1,d2] [--seeds 1,2]

With --carrier handheld a person walks each scenario with the sensors in hand (robot.carrier,
docs/simulation.md "Carriers"): there is no odometry, so a level's heading bias and odometry noise
do not apply (its dropout, clutter, closed door and removed wall do), and the LiDAR and the IMU
make the odometry.
"""
import argparse
import csv
import json
import os
import random
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
PLANS = os.path.join(ROOT, "worlds", "plans")

# The stress levels: heading bias °/m, heading noise °/m, translation noise (share of distance),
# LiDAR dropout, clutter boxes, close a door, remove a wall. Noise None: the scenario default.
LEVELS = [
    dict(bias=0.0, noise=None, translation=None, dropout=0.0, clutter=0, door=False, wall=False),
    dict(bias=1.5, noise=None, translation=None, dropout=0.0, clutter=20, door=False, wall=False),
    dict(bias=1.5, noise=None, translation=None, dropout=0.5, clutter=20, door=True, wall=False),
    dict(bias=-2.0, noise=1.5, translation=0.05, dropout=0.7, clutter=24, door=False, wall=True),
    dict(bias=3.0, noise=None, translation=None, dropout=0.5, clutter=20, door=True, wall=False),
    dict(bias=-3.0, noise=2.0, translation=0.05, dropout=0.6, clutter=24, door=True, wall=True),
]


def door_centres(plan):
    level = plan["levels"][0]
    walls = {w["id"]: w for w in level["walls"]}
    out = []
    for door in level["doors"]:
        w = walls[door["wall"]]
        (x0, y0), (x1, y1) = w["start"], w["end"]
        length = ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
        s = door["offset"] / length
        out.append((x0 + s * (x1 - x0), y0 + s * (y1 - y0)))
    return out


def clutter_boxes(plan, rng, count):
    """Boxes along the rooms' walls, away from doors and the room centres the route passes."""
    rooms = plan["levels"][0]["rooms"]
    doors = door_centres(plan)
    boxes = []
    for _ in range(count * 20):
        if len(boxes) == count:
            break
        room = rng.choice(rooms)
        xs = [p[0] for p in room["outline"]]
        ys = [p[1] for p in room["outline"]]
        lo_x, hi_x, lo_y, hi_y = min(xs), max(xs), min(ys), max(ys)
        if hi_x - lo_x < 2.5 or hi_y - lo_y < 2.5:
            continue
        sx, sy, sz = rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), rng.uniform(0.4, 1.4)
        # Against one of the four walls, 0.05 m off it.
        side = rng.randrange(4)
        if side < 2:
            x = lo_x + 0.05 + sx / 2 if side == 0 else hi_x - 0.05 - sx / 2
            y = rng.uniform(lo_y + 0.3 + sy / 2, hi_y - 0.3 - sy / 2)
        else:
            y = lo_y + 0.05 + sy / 2 if side == 2 else hi_y - 0.05 - sy / 2
            x = rng.uniform(lo_x + 0.3 + sx / 2, hi_x - 0.3 - sx / 2)
        cx, cy = (lo_x + hi_x) / 2, (lo_y + hi_y) / 2
        if abs(x - cx) < 1.2 and abs(y - cy) < 1.2:
            continue
        if any(abs(x - dx) < 1.6 and abs(y - dy) < 1.6 for dx, dy in doors):
            continue
        boxes.append({"shape": "box", "center": [round(x, 3), round(y, 3), round(sz / 2, 3)],
                      "size": [round(sx, 3), round(sy, 3), round(sz, 3)], "yaw": 0.0})
    return boxes


def make_scenario(world, level, seed, out_dir, attempt=0, mount=None, carrier="legged"):
    stress = LEVELS[level]
    bias, dropout, clutter, close_door = stress["bias"], stress["dropout"], stress["clutter"], stress["door"]
    rng = random.Random(f"{world}/{level}/{seed}/{attempt}")
    base = json.load(open(os.path.join(PLANS, f"{world}.asbuilt.json")))
    plan = json.load(open(os.path.join(PLANS, base["plan"])))
    shutil.copy(os.path.join(PLANS, base["plan"]), out_dir)
    scenario = dict(base)
    scenario.pop("$schema", None)
    scenario["seed"] = seed
    if carrier == "handheld":
        scenario["robot"] = {"carrier": "handheld"}
        bias = 0.0  # no odometry to bias
    else:
        scenario["odometry"] = {"heading_bias_deg_per_m": bias}
        if stress["noise"] is not None:
            scenario["odometry"]["heading_noise_deg_per_m"] = stress["noise"]
        if stress["translation"] is not None:
            scenario["odometry"]["translation_noise"] = stress["translation"]
    scenario["lidar"] = {"dropout": dropout}
    if mount is not None:
        scenario["lidar"]["mount"] = mount
    as_built = dict(base.get("as_built", {}))
    as_built["clutter"] = list(as_built.get("clutter", [])) + clutter_boxes(plan, rng, clutter)
    if close_door:
        closed = set(as_built.get("closed_doors", []))
        doors = [d["id"] for d in plan["levels"][0]["doors"] if d["id"] not in closed]
        as_built["closed_doors"] = sorted(closed | {rng.choice(doors)})
    if stress["wall"]:
        # An interior wall (one with a door) that the scenario does not already change.
        changed = set(as_built.get("missing_walls", [])) | {
            w["wall"] for w in as_built.get("wall_shifts", [])}
        with_doors = sorted({d["wall"] for d in plan["levels"][0]["doors"]} - changed)
        as_built["missing_walls"] = sorted(set(as_built.get("missing_walls", [])) |
                                           {rng.choice(with_doors)})
        missing = set(as_built["missing_walls"])
        doors_gone = {d["id"] for d in plan["levels"][0]["doors"] if d["wall"] in missing}
        if "closed_doors" in as_built:
            as_built["closed_doors"] = [d for d in as_built["closed_doors"] if d not in doors_gone]
    scenario["as_built"] = as_built
    name = f"{world}-L{level}-s{seed}" + ("-handheld" if carrier == "handheld" else "")
    path = os.path.join(out_dir, name + ".json")
    json.dump(scenario, open(path, "w"), indent=1)
    return name, path, bias


def read_tum(path):
    rows = []
    for line in open(path):
        if line.strip() and not line.startswith("#"):
            v = [float(x) for x in line.split()]
            rows.append((v[0], v[1], v[2]))
    return rows


def placed_rows(run_dir):
    """estimate.tum's rows the localizer placed: not those written while lost (estimate_states.txt,
    docs/formats.md); every row for runs written before the states were kept."""
    rows = read_tum(os.path.join(run_dir, "estimate.tum"))
    states_path = os.path.join(run_dir, "estimate_states.txt")
    if not os.path.exists(states_path):
        return rows
    states = [line.split()[1] for line in open(states_path)
              if line.strip() and not line.startswith("#")]
    return [r for r, s in zip(rows, states) if s != "lost"]


def nearest(rows, t):
    import bisect
    i = bisect.bisect_left([r[0] for r in rows], t)
    best = min((j for j in (i - 1, i) if 0 <= j < len(rows)), key=lambda j: abs(rows[j][0] - t))
    return rows[best]


def kidnap_suite(args):
    """Each world as built walked once, then again with a kidnap midway into a room at least 4 m
    from where the robot is then; reports detection, relocalization and the error after it."""
    os.makedirs(os.path.join(args.out, "scenarios"), exist_ok=True)
    results = []
    for world in args.worlds.split(","):
        for seed in [int(x) for x in args.seeds.split(",")]:
            base = json.load(open(os.path.join(PLANS, f"{world}.asbuilt.json")))
            plan = json.load(open(os.path.join(PLANS, base["plan"])))
            shutil.copy(os.path.join(PLANS, base["plan"]), os.path.join(args.out, "scenarios"))
            base.pop("$schema", None)
            base["seed"] = seed
            plain = os.path.join(args.out, "scenarios", f"{world}-s{seed}.json")
            json.dump(base, open(plain, "w"), indent=1)
            plain_run = os.path.join(args.out, "runs", f"{world}-s{seed}")
            subprocess.run([args.isg, "run", plain, "-o", plain_run, "--force", "-q",
                            "--threads", args.threads], check=True, capture_output=True)
            duration = json.load(open(os.path.join(plain_run, "metrics.json")))["sim_seconds"]
            when = round(duration / 2, 1)
            _, x, y = nearest(read_tum(os.path.join(plain_run, "groundtruth.tum")), when)
            rng = random.Random(f"kidnap/{world}/{seed}")
            distance = {}
            for room in plan["levels"][0]["rooms"]:
                xs = [p[0] for p in room["outline"]]
                ys = [p[1] for p in room["outline"]]
                cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
                distance[room["id"]] = ((cx - x) ** 2 + (cy - y) ** 2) ** 0.5
            # A room at least 4 m away; in a small building, the farthest one.
            far = sorted(r for r, d in distance.items() if d >= 4.0)
            target = rng.choice(far) if far else max(distance, key=distance.get)
            base["robot"] = {"kidnap": [{"time": when, "to": {"room": target}}]}
            name = f"{world}-s{seed}-kidnap"
            path = os.path.join(args.out, "scenarios", name + ".json")
            json.dump(base, open(path, "w"), indent=1)
            run_dir = os.path.join(args.out, "runs", name)
            subprocess.run([args.isg, "run", path, "-o", run_dir, "--force", "-q",
                            "--threads", args.threads], check=True, capture_output=True)
            m = json.load(open(os.path.join(run_dir, "metrics.json")))
            truth = read_tum(os.path.join(run_dir, "groundtruth.tum"))
            after = [r for r in placed_rows(run_dir) if r[0] >= when]
            errors = [((r[1] - g[1]) ** 2 + (r[2] - g[2]) ** 2) ** 0.5
                      for r in after for g in [nearest(truth, r[0])]]
            lost = [t for t in m.get("lost_at", []) if t >= when]
            back = [t for t in m.get("relocalized_at", []) if t >= when]
            row = dict(run=name, kidnap_at=when, to=target,
                       detected_after=round(lost[0] - when, 1) if lost else None,
                       relocalized_after=round(back[0] - when, 1) if back else None,
                       wrong=m.get("wrongly_localized"),
                       time_wrong=m.get("time_wrongly_localized"),
                       max_error_after=round(max(errors), 2) if errors else None,
                       rows_over_1m_after=sum(e > 1.0 for e in errors),
                       ape_B=m["ape_B"]["rmse"] if "ape_B" in m else None)
            results.append(row)
            print(row, flush=True)
    bad = [r for r in results if r["wrong"] or r["relocalized_after"] is None or
           r["relocalized_after"] > 60.0]
    print(f"\n{len(results)} kidnaps: {len(results) - len(bad)} detected and relocalized "
          f"within 60 s with no wrong stretch; {len(bad)} not")
    return 1 if bad else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--isg", default=os.path.join(ROOT, "build", "cli", "isg"))
    parser.add_argument("--out", required=True, help="folder for scenarios, runs and summary")
    parser.add_argument("--worlds", default="d1,d2,d3,d4,d5,d6")
    parser.add_argument("--seeds", default="1,2")
    parser.add_argument("--levels", default=",".join(str(i) for i in range(len(LEVELS))))
    parser.add_argument("--threads", default="2")
    parser.add_argument("--lidar-mount", default=None, metavar="X,Y,Z,ROLL,PITCH,YAW",
                        help="the LiDAR's mount on the robot for every scenario (lidar.mount, "
                        "docs/formats.md), e.g. 0,0,0.14,0,0,0 for the puck on the body; "
                        "default: each world's")
    parser.add_argument("--carrier", choices=["legged", "handheld"], default="legged",
                        help="what carries the sensors (robot.carrier); handheld: no odometry")
    parser.add_argument("--kidnap", action="store_true",
                        help="the kidnap suite instead: each world as built, kidnapped midway")
    args = parser.parse_args()
    mount = None
    if args.lidar_mount is not None:
        mount = [float(x) for x in args.lidar_mount.split(",")]
        if len(mount) != 6:
            parser.error("--lidar-mount takes six numbers: x,y,z,roll,pitch,yaw")
    if args.kidnap:
        return kidnap_suite(args)
    scenarios = os.path.join(args.out, "scenarios")
    os.makedirs(scenarios, exist_ok=True)
    rows = []

    def write_summary():
        # After every run, so that an interrupted suite keeps what it measured.
        fields = ["run", "bias", "localized", "wrong", "time_wrong", "max_error", "ape_B", "ape_M",
                  "ape_odometry", "lost", "status", "rtf", "error"]
        with open(os.path.join(args.out, "summary.csv"), "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=fields)
            writer.writeheader()
            writer.writerows(rows)

    for world in args.worlds.split(","):
        for level in [int(x) for x in args.levels.split(",")]:
            for seed in [int(x) for x in args.seeds.split(",")]:
                # A draw whose clutter or closed door cuts the route is drawn again; in a
                # building where every door is the only way into some room, the first draw that
                # runs at all (skipping rooms) is taken.
                def run(attempt):
                    name, path, bias = make_scenario(world, level, seed, scenarios, attempt, mount,
                                                     args.carrier)
                    run_dir = os.path.join(args.out, "runs", name)
                    result = subprocess.run([args.isg, "run", path, "-o", run_dir, "--force",
                                             "-q", "--threads", args.threads],
                                            capture_output=True, text=True)
                    return name, bias, run_dir, result
                fallback = None
                for attempt in range(8):
                    name, bias, run_dir, result = run(attempt)
                    if "cannot be reached" not in result.stderr:
                        break
                    if result.returncode == 0 and fallback is None:
                        fallback = attempt
                else:
                    if result.returncode != 0 and fallback is not None:
                        name, bias, run_dir, result = run(fallback)
                if result.returncode != 0:
                    print(f"{name}: exit {result.returncode}: {result.stderr.strip()[:200]}")
                    rows.append({"run": name, "bias": bias, "error": result.stderr.strip()[:200]})
                    write_summary()
                    continue
                m = json.load(open(os.path.join(run_dir, "metrics.json")))
                row = {
                    "run": name, "bias": bias, "localized": m["localized"],
                    "wrong": m.get("wrongly_localized", False),
                    "time_wrong": m.get("time_wrongly_localized", 0.0),
                    "max_error": m.get("max_error_B", ""),
                    "ape_B": m["ape_B"]["rmse"] if "ape_B" in m else "",
                    "ape_M": m["ape_M_se3"]["rmse"] if "ape_M_se3" in m else "",
                    "ape_odometry": (m["ape_odometry_from_true_start"]["rmse"]
                                     if "ape_odometry_from_true_start" in m else float("nan")),
                    "lost": len(m.get("lost_at", [])), "status": m.get("matching_status", ""),
                    "rtf": m["real_time_factor"],
                }
                rows.append(row)
                write_summary()
                print(f"{name}: localized={row['localized']} wrong={row['wrong']} "
                      f"max_error={row['max_error'] if row['max_error'] == '' else round(row['max_error'], 2)} "
                      f"ape_B={row['ape_B']} ape_M={row['ape_M']} odo={row['ape_odometry']:.2f} "
                      f"lost={row['lost']} rtf={row['rtf']:.1f}", flush=True)
    done = [r for r in rows if "error" not in r]
    localized = [r for r in done if r["localized"]]
    wrong = [r for r in done if r["wrong"]]
    print(f"\n{len(done)} runs ({len(rows) - len(done)} failed to start): {len(localized)} localized, "
          f"{len(wrong)} wrongly localized")
    print("bias °/m | runs | localized | wrong | median APE in M | median odometry APE")
    for bias in sorted({r["bias"] for r in done}):
        group = [r for r in done if r["bias"] == bias]
        med = lambda xs: sorted(xs)[len(xs) // 2] if xs else float("nan")
        ape_m = med([r["ape_M"] for r in group if r["ape_M"] != ""])
        odo = med([r["ape_odometry"] for r in group])
        print(f"{bias:8.1f} | {len(group):4d} | {sum(r['localized'] for r in group):9d} | "
              f"{sum(r['wrong'] for r in group):5d} | {ape_m:15.3f} | {odo:19.3f}")
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main())
