#!/usr/bin/env python3
"""An MCAP file from `isg export --mcap` read by the reference readers from npm (ci/oracles,
pinned: @mcap/core, @mcap/nodejs, @foxglove/rosmsg, @foxglove/rosmsg2-serialization, @foxglove/crc,
@foxglove/wasm-zstd, @foxglove/wasm-lz4), through cli/tests/mcap_oracle.js.

Simulates D1 as built (uncompressed PCD, so that this script can read the scans itself), exports
it uncompressed, with zstd and with lz4, and checks for each: the header (profile ros2, our mark),
the statistics against the messages, the chunk CRCs (indexed reader), the data section's CRC, a
stream reader's walk through every record; every topic with its ROS 2 type, CDR encoding and a
count equal to the dataset's; log and publish times equal to each message's stamp, in order. Then
every message against the dataset: every cloud's points byte for byte (SHA-256 of the PCD's
body) with the Velodyne driver's layout, every IMU row exactly, every odometry and ground-truth
pose (positions exactly, quaternions within 1e-12 of the TUM files' normalised ones), /tf equal
to /odom, the mounts equal to metadata.json's, the metadata equal to metadata.json but its PCD
encoding. The three compressions must decode to the same messages, an export run twice must give
the same bytes, and so must the compressed dataset of the same seed.
Exit 77 (skipped) when node or the npm oracles are not installed (ci/install-deps installs them).
usage: mcap_oracle.py --isg ISG --oracles NODE_MODULES_DIR [--duration S]
"""
import argparse
import hashlib
import json
import math
import os
import pathlib
import shutil
import sys
import tempfile

from oracle_checks import check, read_mcap_with_npm, run, verdict

OFFSET = 1000000000  # isg export's default --stamp-offset, whole seconds
MODULES = ["@mcap/core", "@mcap/nodejs", "@foxglove/rosmsg", "@foxglove/rosmsg2-serialization",
           "@foxglove/crc", "@foxglove/wasm-zstd", "@foxglove/wasm-lz4"]


def rows(path, separator=None, skip_first=False):
    lines = [l for l in path.read_text().splitlines() if l.strip() and not l.startswith("#")]
    return [[float(x) for x in l.split(separator)] for l in lines[1 if skip_first else 0:]]


def pcd_body(path):
    data = path.read_bytes()
    return data[data.index(b"DATA binary\n") + len(b"DATA binary\n"):]


def stamp_ns(t):
    return OFFSET * 1000000000 + round(t * 1e9)


def same_stamp(stamp, t):
    return stamp[0] * 1000000000 + stamp[1] == stamp_ns(t)


def same_quaternion(got, row):
    norm = math.sqrt(sum(v * v for v in row))
    q = [v / norm for v in row]
    if q[3] < 0:
        q = [-v for v in q]
    return all(abs(a - b) < 1e-12 for a, b in zip(got, q))


def check_file(name, got, ds, compression):
    scans, imu = rows(ds / "scans.tum"), rows(ds / "imu.csv", ",", skip_first=True)
    odom, gt = rows(ds / "odometry.tum"), rows(ds / "groundtruth.tum")
    meta = json.loads((ds / "metadata.json").read_text())
    check(got["header"]["profile"] == "ros2" and "written by isg" in got["header"]["library"],
          f"{name}: header {got['header']}")
    check(got["compression"] == [compression], f"{name}: chunks compressed {got['compression']}")
    stats = got["statistics"]
    total = sum(len(m) for m in got["messages"].values())
    check(stats["message_count"] == total,
          f"{name}: statistics say {stats['message_count']} messages, {total} read")
    check(stats["chunk_count"] == got["chunk_indexes"] > 1, f"{name}: chunks {stats}")
    check(got["data_section_crc_ok"], f"{name}: data section CRC")
    check(got["stream_done"] and got["stream_messages"] == total,
          f"{name}: the stream reader read {got['stream_messages']} messages")
    check(got["log_time_errors"] == 0, f"{name}: {got['log_time_errors']} log times off")
    expected = {
        "/velodyne_points": ("sensor_msgs/msg/PointCloud2", len(scans)),
        "/imu/data": ("sensor_msgs/msg/Imu", len(imu)),
        "/odom": ("nav_msgs/msg/Odometry", len(odom)),
        "/tf": ("tf2_msgs/msg/TFMessage", len(odom)),
        "/tf_static": ("tf2_msgs/msg/TFMessage", 1),
        "/ground_truth": ("nav_msgs/msg/Odometry", len(gt)),
        "/isg/metadata": ("std_msgs/msg/String", 1),
    }
    channels = got["channels"]
    check(set(channels) == set(expected), f"{name}: topics {sorted(channels)}")
    for topic, (kind, count) in expected.items():
        c = channels.get(topic, {})
        check(c.get("type") == kind and c.get("message_encoding") == "cdr" and
              c.get("schema_encoding") == "ros2msg", f"{name}: {topic} is {c}")
        check(c.get("count") == count == len(got["messages"].get(topic, [])),
              f"{name}: {topic} {c.get('count')} messages, dataset has {count}")
    check("durability: 1" in channels["/tf_static"]["metadata"].get("offered_qos_profiles", ""),
          f"{name}: /tf_static not offered as latched")
    m = got["messages"]

    layout = [["x", 0, 7, 1], ["y", 4, 7, 1], ["z", 8, 7, 1], ["intensity", 12, 7, 1],
              ["ring", 16, 4, 1], ["time", 18, 7, 1]]
    for k, cloud in enumerate(m["/velodyne_points"]):
        body = pcd_body(ds / "scans" / f"{k:06d}.pcd")
        ok = (cloud["fields"] == layout and cloud["point_step"] == 22 and cloud["height"] == 1 and
              not cloud["is_bigendian"] and cloud["is_dense"] and cloud["frame"] == "velodyne" and
              cloud["width"] * 22 == len(body) == cloud["row_step"] and
              same_stamp(cloud["stamp"], scans[k][0]) and
              cloud["data_sha256"] == hashlib.sha256(body).hexdigest())
        check(ok, f"{name}: cloud {k} differs from its PCD: {dict(cloud, fields=None)}")

    gyro_var = meta["imu"]["gyroscope_noise_density"] ** 2 * meta["imu"]["rate_hz"]
    accel_var = meta["imu"]["accelerometer_noise_density"] ** 2 * meta["imu"]["rate_hz"]
    for i, (msg, row) in enumerate(zip(m["/imu/data"], imu)):
        ok = (same_stamp(msg["stamp"], row[0]) and msg["accelerometer"] == row[1:4] and
              msg["gyroscope"] == row[4:7] and msg["frame"] == "imu" and
              msg["orientation_covariance"][0] == -1.0 and
              msg["gyroscope_covariance"][0::4] == [gyro_var] * 3 and
              msg["accelerometer_covariance"][0::4] == [accel_var] * 3)
        check(ok, f"{name}: imu {i}: {msg} vs {row}")

    for topic, truth, frame in (("/odom", odom, "odom"), ("/ground_truth", gt, "plan")):
        for i, (msg, row) in enumerate(zip(m[topic], truth)):
            ok = (same_stamp(msg["stamp"], row[0]) and msg["pose"][:3] == row[1:4] and
                  same_quaternion(msg["pose"][3:], row[4:8]) and msg["frame"] == frame and
                  msg["child"] == "base_link")
            check(ok, f"{name}: {topic} {i}: {msg} vs {row}")
    for i, (tf, msg) in enumerate(zip(m["/tf"], m["/odom"])):
        check(len(tf) == 1 and tf[0]["parent"] == "odom" and tf[0]["child"] == "base_link" and
              tf[0]["translation"] + tf[0]["rotation"] == msg["pose"] and
              tf[0]["stamp"] == msg["stamp"], f"{name}: /tf {i} is not /odom's pose")

    mounts = {t["child"]: t for t in m["/tf_static"][0]}
    check(set(mounts) == {"velodyne", "imu"}, f"{name}: static children {sorted(mounts)}")
    for child, key in (("velodyne", "R_T_L"), ("imu", "R_T_I")):
        matrix = meta["extrinsics"][key]["matrix"]
        check(mounts[child]["parent"] == "base_link" and
              mounts[child]["translation"] == [matrix[0][3], matrix[1][3], matrix[2][3]],
              f"{name}: {child} mount {mounts[child]}")
    made = dict(meta)
    made["lidar"] = {k: v for k, v in meta["lidar"].items() if k != "pcd_data"}
    check(json.loads(m["/isg/metadata"][0]) == made, f"{name}: /isg/metadata differs")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--isg", required=True)
    parser.add_argument("--oracles", required=True, help="ci/oracles/node_modules")
    parser.add_argument("--duration", help="seconds of the route (default: all of it)")
    args = parser.parse_args()
    if shutil.which("node") is None or not all(
            os.path.isdir(os.path.join(args.oracles, m)) for m in MODULES):
        print("skipped: node or the npm oracles are not installed (ci/install-deps)")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        duration = ["--duration", args.duration] if args.duration else []
        ds = tmp / "ds"
        run([args.isg, "simulate", "builtin:d1.asbuilt", "-o", str(ds), "--pcd", "binary", "-q"] +
            duration)
        decoded = {}
        for compression in ("none", "zstd", "lz4"):
            mcap = tmp / f"d1-{compression}.mcap"
            out = run([args.isg, "export", str(ds), "--mcap", str(mcap), "--compression",
                       compression, "-q"])
            check("wrote" in out and "/velodyne_points" in out, f"export summary: {out}")
            got = read_mcap_with_npm(mcap, args.oracles)
            check_file(mcap.name, got, ds, "" if compression == "none" else compression)
            decoded[compression] = got["messages"]
        check(decoded["none"] == decoded["zstd"] == decoded["lz4"],
              "the three compressions decode to different messages")

        # One seed, one file: the export run again, and the compressed dataset of the same seed.
        run([args.isg, "export", str(ds), "--mcap", str(tmp / "again.mcap"), "-q"])
        check((tmp / "d1-zstd.mcap").read_bytes() == (tmp / "again.mcap").read_bytes(),
              "two exports of one dataset differ")
        run([args.isg, "simulate", "builtin:d1.asbuilt", "-o", str(tmp / "dsc"), "-q"] + duration)
        run([args.isg, "export", str(tmp / "dsc"), "--mcap", str(tmp / "dsc.mcap"), "-q"])
        check((tmp / "d1-zstd.mcap").read_bytes() == (tmp / "dsc.mcap").read_bytes(),
              "MCAP files of a binary and a compressed dataset of one seed differ")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
