#!/usr/bin/env python3
"""A run's MCAP file (`isg run --mcap`, `isg export RUN_DIR --mcap`) read by the reference readers
from npm (ci/oracles, pinned: @mcap/core, @mcap/nodejs, @foxglove/rosmsg2-serialization, and ajv
with @foxglove/schemas' JSON Schemas), through cli/tests/run_mcap_oracle.js.

Runs D1 as built with --mcap and checks: every topic of docs/foxglove.md with its type and
encodings; every JSON message valid against the schema the file carries and against Foxglove's
own (and both schemas rejecting a message without a required field); log time = the message's
timestamp, in order; the transforms against the run folder (map -> base_link = estimate_map.tum
row for row, plan -> map composed with it = estimate.tum, base_link -> velodyne once); the paths'
ends against the TUM files; the last S-Graph against sgraph.json; the matcher's last candidates
drawn one by one with one best; the log against metrics.json's
matching events; the plan against agraph.json (the first wall face by hand); the deviation labels
against deviations.json; the scans' frame and layout. The same seed run again gives the same
bytes. `isg export RUN_DIR --mcap` gives the same plan, A-Graph, deviations and final S-Graph, the
same transforms to the TUM files' rounding, and no scans; a run folder with --rosbag is refused.
docs/foxglove-layout.json names only topics a run's file has.
Exit 77 (skipped) when node or the npm oracles are not installed (ci/install-deps installs them).
usage: run_mcap_oracle.py --isg ISG --oracles NODE_MODULES_DIR
"""
import argparse
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

from oracle_checks import check, run, verdict

OFFSET_NS = 1000000000 * 1000000000  # isg's default stamp offset, in nanoseconds
MODULES = ["@mcap/core", "@mcap/nodejs", "@foxglove/rosmsg", "@foxglove/rosmsg2-serialization",
           "@foxglove/wasm-zstd", "@foxglove/wasm-lz4", "ajv", "@foxglove/schemas"]
TOPICS = {
    "/tf": "foxglove.FrameTransform",
    "/plan": "foxglove.SceneUpdate",
    "/agraph": "foxglove.SceneUpdate",
    "/sgraph": "foxglove.SceneUpdate",
    "/deviations": "foxglove.SceneUpdate",
    "/isg/matching": "isg.Matching",
    "/isg/candidates": "foxglove.SceneUpdate",
    "/isg/log": "foxglove.Log",
    "/groundtruth/path": "foxglove.PosesInFrame",
    "/estimate/path": "foxglove.PosesInFrame",
    "/estimate_map/path": "foxglove.PosesInFrame",
    "/velodyne_points": "sensor_msgs/msg/PointCloud2",
}
TUM_POSITION = 1.5e-6  # m: a TUM file keeps micrometres


def tum(path):
    out = []
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            v = [float(x) for x in line.split()]
            out.append((v[0], v[1:4], v[4:8]))
    return out


def stamp_ns(t):
    return OFFSET_NS + round(t * 1e9)


def time_ns(stamp):
    return stamp["sec"] * 1000000000 + stamp["nsec"]


def xyz(v):
    return [v["x"], v["y"], v["z"]]


def quat(q):
    return [q["x"], q["y"], q["z"], q["w"]]


def close(a, b, tol):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def rotate(q, v):
    x, y, z, w = q
    # v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)
    u = [x, y, z]
    c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    cc = [u[1] * c[2] - u[2] * c[1], u[2] * c[0] - u[0] * c[2], u[0] * c[1] - u[1] * c[0]]
    return [v[i] + 2 * w * c[i] + 2 * cc[i] for i in range(3)]


def compose(a_t, a_q, b_t):
    r = rotate(a_q, b_t)
    return [a_t[i] + r[i] for i in range(3)]


def read(mcap, modules):
    script = pathlib.Path(__file__).with_name("run_mcap_oracle.js")
    return json.loads(run(["node", str(script), str(mcap), modules]))


def values(out, topic):
    return [m["value"] for m in out["messages"].get(topic, [])]


def check_file(out, name, expect_topics):
    check(set(out["channels"]) == set(expect_topics),
          f"{name}: topics {sorted(out['channels'])}, expected {sorted(expect_topics)}")
    for topic in expect_topics:
        channel = out["channels"].get(topic, {})
        check(channel.get("type") == TOPICS[topic], f"{name}: {topic} type {channel.get('type')}")
        json_topic = TOPICS[topic] != "sensor_msgs/msg/PointCloud2"
        check(channel.get("message_encoding") == ("json" if json_topic else "cdr") and
              channel.get("schema_encoding") == ("jsonschema" if json_topic else "ros2msg"),
              f"{name}: {topic} encodings {channel}")
        check(channel.get("count", 0) >= 1, f"{name}: {topic} has no message")
        if TOPICS[topic].startswith("foxglove."):
            check(channel.get("foxglove_schema"), f"{name}: {topic}: no Foxglove schema to check")
    check(not out["invalid"], f"{name}: messages failing a schema: {out['invalid'][:3]}")
    check(all(out["rejects_broken"].values()) and out["rejects_broken"],
          f"{name}: a schema accepts a message without a required field: {out['rejects_broken']}")
    check(out["log_time_errors"] == 0, f"{name}: {out['log_time_errors']} log time errors")
    # Log time = the message's own timestamp (each scene entity's for a scene update).
    wrong = 0
    for topic, messages in out["messages"].items():
        for m in messages:
            v = m["value"]
            stamps = ([time_ns(e["timestamp"]) for e in v["entities"]] if "entities" in v else
                      [v["stamp"][0] * 1000000000 + v["stamp"][1]] if "stamp" in v else
                      [time_ns(v["timestamp"])])
            wrong += any(s != int(m["log_time"]) for s in stamps)
    check(wrong == 0, f"{name}: {wrong} messages stamped other than their log time")


def transforms(out, parent, child):
    return [t for t in values(out, "/tf")
            if t["parent_frame_id"] == parent and t["child_frame_id"] == child]


def entity(update, entity_id):
    found = [e for e in update["entities"] if e["id"] == entity_id]
    return found[0] if found else None


def check_live(out, run_dir):
    name = "isg run --mcap"
    check_file(out, name, TOPICS)
    estimate_map = tum(run_dir / "estimate_map.tum")
    estimate = tum(run_dir / "estimate.tum")
    truth = tum(run_dir / "groundtruth.tum")
    graph = json.loads((run_dir / "sgraph.json").read_text())
    agraph = json.loads((run_dir / "agraph.json").read_text())
    metrics = json.loads((run_dir / "metrics.json").read_text())
    deviations = json.loads((run_dir / "deviations.json").read_text())

    check(len(transforms(out, "base_link", "velodyne")) == 1, f"{name}: base_link -> velodyne once")
    map_base = transforms(out, "map", "base_link")
    check(len(map_base) == len(estimate_map),
          f"{name}: {len(map_base)} map -> base_link, estimate_map.tum has {len(estimate_map)}")
    off = sum(time_ns(t["timestamp"]) != stamp_ns(row[0]) or
              not close(xyz(t["translation"]), row[1], TUM_POSITION)
              for t, row in zip(map_base, estimate_map))
    check(off == 0, f"{name}: {off} map -> base_link differ from estimate_map.tum")
    plan_map = transforms(out, "plan", "map")
    check(len(plan_map) == len(estimate),
          f"{name}: {len(plan_map)} plan -> map, estimate.tum has {len(estimate)}")
    by_stamp = {time_ns(t["timestamp"]): t for t in map_base}
    off = 0
    for t, row in zip(plan_map, estimate):
        m = by_stamp.get(time_ns(t["timestamp"]))
        composed = compose(xyz(t["translation"]), quat(t["rotation"]), xyz(m["translation"]))
        off += m is None or not close(composed, row[1], 1e-5)
    check(off == 0, f"{name}: {off} plan -> map -> base_link differ from estimate.tum")

    last = values(out, "/estimate/path")[-1]["poses"]
    check(last and close(xyz(last[-1]["position"]), estimate[-1][1], TUM_POSITION),
          f"{name}: the estimate path does not end at estimate.tum's last row")
    last = values(out, "/estimate_map/path")[-1]["poses"]
    check(close(xyz(last[-1]["position"]), estimate_map[-1][1], TUM_POSITION),
          f"{name}: the map path does not end at estimate_map.tum's last row")
    gt = values(out, "/groundtruth/path")
    check(len(gt) == 1 and gt[0]["frame_id"] == "plan", f"{name}: one ground truth path in plan")
    poses = gt[0]["poses"]
    check(close(xyz(poses[0]["position"]), truth[0][1], TUM_POSITION) and
          close(xyz(poses[-1]["position"]), truth[-1][1], TUM_POSITION),
          f"{name}: the ground truth path's ends are not groundtruth.tum's")
    steps = [math.dist(xyz(a["position"]), xyz(b["position"])) for a, b in zip(poses, poses[1:])]
    check(all(s >= 0.1 - 1e-12 for s in steps[:-1]), f"{name}: path poses closer than 0.1 m")

    sgraph = values(out, "/sgraph")
    check(len(sgraph) == len(values(out, "/estimate/path")),
          f"{name}: {len(sgraph)} S-Graphs, {len(values(out, '/estimate/path'))} paths")
    final = sgraph[-1]
    keyframes = entity(final, "sgraph/keyframes")
    check(len(keyframes["spheres"]) == len(graph["keyframes"]),
          f"{name}: final S-Graph keyframes {len(keyframes['spheres'])} != sgraph.json")
    planes = entity(final, "sgraph/planes")
    check(len(planes["triangles"][0]["points"]) == 6 * len(graph["planes"]),
          f"{name}: final S-Graph planes drawn != sgraph.json's {len(graph['planes'])}")
    check(len(entity(final, "sgraph/rooms")["spheres"]) == len(graph["rooms"]),
          f"{name}: final S-Graph rooms != sgraph.json")
    edges = entity(final, "sgraph/edges")["lines"][0]["points"]
    observed = sum(len(k["plane_ids"]) for k in graph["keyframes"])
    check(observed > 0 and len(edges) >= 2 * observed,
          f"{name}: {len(edges) // 2} S-Graph edges for {observed} keyframe-plane observations")
    grown = [len(entity(u, "sgraph/keyframes")["spheres"]) for u in sgraph]
    check(grown == sorted(grown) and grown[0] < grown[-1], f"{name}: keyframes do not grow")

    matching = values(out, "/isg/matching")[-1]
    check(matching["status"] == graph["matching"]["status"] and
          matching["localized"] == graph["matching"]["localized"],
          f"{name}: last matching state {matching['status']} != sgraph.json")
    candidates = graph["matching"]["last_match"]["candidates"]
    drawn = entity(values(out, "/isg/candidates")[-1], "matching/candidates")
    check(len(drawn["texts"]) == len(candidates) and
          sum(t["text"].startswith("best") for t in drawn["texts"]) == 1,
          f"{name}: {len(drawn['texts'])} candidates drawn, sgraph.json has {len(candidates)}")
    check(len(values(out, "/isg/candidates")) == len(values(out, "/isg/matching")),
          f"{name}: candidates not drawn with every matching state")
    events = metrics["matching_events"]
    logs = out["messages"]["/isg/log"]
    check(len(logs) == len(events), f"{name}: {len(logs)} log lines, {len(events)} events")
    check(all(m["value"]["message"].startswith(e["status"]) and
              int(m["log_time"]) >= stamp_ns(e["stamp"]) for m, e in zip(logs, events)),
          f"{name}: the log does not follow metrics.json's matching events")

    plan = values(out, "/plan")[0]
    faces = entity(plan, "plan/walls")["triangles"][0]["points"]
    segments = sum(len(s["segments"]) for s in agraph["nodes"]["wall_surfaces"])
    check(len(faces) == 6 * segments, f"{name}: {len(faces)} wall face corners for {segments}")
    first = agraph["nodes"]["wall_surfaces"][0]
    (ax, ay), (bx, by) = first["segments"][0]
    z0, z1 = first["z"]
    expected = [[ax, ay, z0], [bx, by, z0], [bx, by, z1], [ax, ay, z0], [bx, by, z1], [ax, ay, z1]]
    check(all(close(xyz(p), e, 1e-12) for p, e in zip(faces, expected)),
          f"{name}: the first wall face is not {expected}")
    check(len(entity(plan, "plan/doorways")["cubes"]) == len(agraph["nodes"]["doorways"]),
          f"{name}: doorways drawn != agraph.json")
    check(len(entity(plan, "plan/rooms")["texts"]) == len(agraph["nodes"]["rooms"]),
          f"{name}: room labels != agraph.json")
    nodes = entity(values(out, "/agraph")[0], "agraph/nodes")["spheres"]
    check(len(nodes) == sum(len(v) for v in agraph["nodes"].values()),
          f"{name}: A-Graph nodes drawn != agraph.json")
    labels = entity(values(out, "/deviations")[0], "deviations/walls")["texts"]
    deviating = [w for w in deviations["walls"] if w["status"] not in ("as_planned", "not_seen")]
    check(len(labels) == len(deviating), f"{name}: {len(labels)} labels, {len(deviating)} deviating")

    clouds = values(out, "/velodyne_points")
    check(all(c["frame"] == "velodyne" and c["point_step"] == 22 and c["width"] > 1000 and
              c["bytes"] == 22 * c["width"] for c in clouds), f"{name}: a scan is not whole")
    check(len(clouds) <= len(sgraph) + 1, f"{name}: {len(clouds)} scans for {len(sgraph)} snapshots")


def check_export(out, live):
    name = "isg export RUN_DIR --mcap"
    check_file(out, name, [t for t in TOPICS if t != "/velodyne_points"])
    for topic in ("/plan", "/agraph", "/deviations"):
        check(values(out, topic) == values(live, topic), f"{name}: {topic} differs from the run's")
    for topic in ("/sgraph", "/isg/candidates"):
        check(values(out, topic)[-1] == values(live, topic)[-1],
              f"{name}: the last {topic} differs from the run's")
    planes = [len(entity(u, "sgraph/planes")["triangles"][0]["points"]) // 6
              if entity(u, "sgraph/planes")["triangles"] else 0 for u in values(out, "/sgraph")]
    check(planes == sorted(planes) and planes[0] < planes[-1],
          f"{name}: the wall planes do not appear as the keyframes observe them")
    exported = transforms(out, "map", "base_link")
    lived = transforms(live, "map", "base_link")
    check(len(exported) == len(lived) and
          all(t["timestamp"] == u["timestamp"] and
              close(xyz(t["translation"]), xyz(u["translation"]), TUM_POSITION)
              for t, u in zip(exported, lived)),
          f"{name}: map -> base_link differ from the run's beyond the TUM files' rounding")
    check(len(transforms(out, "plan", "map")) == len(transforms(live, "plan", "map")),
          f"{name}: plan -> map count differs from the run's")


def check_layout():
    """docs/foxglove-layout.json is JSON and names only topics a run's file has."""
    layout = json.loads((pathlib.Path(__file__).resolve().parents[2] / "docs" /
                         "foxglove-layout.json").read_text())
    named = set()
    for panel, config in layout["configById"].items():
        named |= set(config.get("topics", {}))
        named |= {config[k] for k in ("topicPath", "topicToRender") if k in config}
    check(named and named <= set(TOPICS), f"the layout names topics no run has: {named - set(TOPICS)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--isg", required=True)
    parser.add_argument("--oracles", required=True, help="node_modules with the npm readers")
    args = parser.parse_args()
    if shutil.which("node") is None or not all(
            (pathlib.Path(args.oracles) / m).is_dir() for m in MODULES):
        print("skipped: node or the npm oracles are missing (run ci/install-deps)")
        return 77
    oracles = os.path.abspath(args.oracles)
    check_layout()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for name in ("a", "b"):
            run([args.isg, "run", "builtin:d1.asbuilt", "--seed", "1", "-q", "-o",
                 str(tmp / name), "--mcap", str(tmp / f"{name}.mcap")])
        check((tmp / "a.mcap").read_bytes() == (tmp / "b.mcap").read_bytes(),
              "the same seed gave different MCAP files")
        live = read(tmp / "a.mcap", oracles)
        check_live(live, tmp / "a")
        run([args.isg, "export", str(tmp / "a"), "--mcap", str(tmp / "e.mcap"), "-q"])
        check_export(read(tmp / "e.mcap", oracles), live)
        refused = subprocess.run([args.isg, "export", str(tmp / "a"), "--rosbag",
                                  str(tmp / "x.bag")], capture_output=True, text=True)
        check(refused.returncode == 1 and "--rosbag takes a dataset folder" in refused.stderr and
              not (tmp / "x.bag").exists(),
              f"a run folder with --rosbag: {refused.returncode} {refused.stderr}")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
