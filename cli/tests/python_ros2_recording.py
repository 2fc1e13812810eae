#!/usr/bin/python3
"""Writes a dataset of ours as a ROS 2 robot with a Hesai PandarXT-32 would record it, with
Python's standard library only (sqlite3, struct): another writer than ours, and CDR encoded here
by hand, for the ROS 2 import's tests.

usage: python_ros2_recording.py DATASET_DIR OUT [--split] [--big-endian] [--no-static]
                                [--short-cloud K]

DATASET_DIR must hold binary PCD scans (isg simulate --pcd binary). OUT is one .db3 file, or with
--split a rosbag2 folder: metadata.yaml (rosbag2_bagfile_information, storage sqlite3) and two
.db3 files, the second holding the messages recorded after the middle of the walk.

The recording, in the Hesai ROS 2 driver's conventions and a handheld rig's (no odometry):
  /hesai/pandar   sensor_msgs/msg/PointCloud2 in "PandarXT-32": x y z float32 at 0 4 8, intensity
                  float32 at 16, timestamp float64 at 24 (seconds since the epoch, each point's),
                  ring uint16 at 32, point_step 48 (PCL's aligned PointXYZIT); stamped at the
                  start of its turn; recorded 30 ms later.
  /alphasense/imu sensor_msgs/msg/Imu in "imu_sensor_frame", no orientation; recorded 2 ms later.
  /ground_truth   nav_msgs/msg/Odometry world -> base_link.
  /tf_static      tf2_msgs/msg/TFMessage: base_link -> PandarXT-32 and base_link ->
                  imu_sensor_frame (left out with --no-static: the import is then given them).
  /rosout         rcl_interfaces/msg/Log: a topic the import has no use for.
--big-endian    every message's CDR in big-endian (encapsulation CDR_BE), as the format allows.
--short-cloud K cloud K's data one point shorter than its width says.
"""
import argparse
import array
import json
import math
import os
import sqlite3
import struct

from rotation_text import quaternion

EPOCH = 1650000000  # recordings are stamped in real time: 2022-04-15


class Cdr:
    """A CDR (XCDR1) stream: primitives aligned to their size from after the 4-byte header."""

    def __init__(self, big_endian):
        self.order = ">" if big_endian else "<"
        self.body = bytearray()
        self.head = b"\x00\x00\x00\x00" if big_endian else b"\x00\x01\x00\x00"

    def put(self, fmt, *values):
        size = struct.calcsize("<" + fmt.lstrip("0123456789")[0])
        self.body += b"\x00" * (-len(self.body) % size)
        self.body += struct.pack(self.order + fmt, *values)

    def string(self, text):
        data = text.encode() + b"\x00"
        self.put("I", len(data))
        self.body += data

    def blob(self, data):
        self.put("I", len(data))
        self.body += data

    def bytes(self):
        return self.head + bytes(self.body)


def header(cdr, t, frame):
    sec = int(math.floor(t))
    cdr.put("i", EPOCH + sec)
    cdr.put("I", int(round((t - sec) * 1e9)) % 1000000000)
    cdr.string(frame)


def to_ns(t):
    return EPOCH * 1000000000 + int(round(t * 1e9))


def cloud(t, points, big_endian, short):
    """The Hesai layout of a scan's 22-byte points (x y z intensity float32, ring uint16, time)."""
    n = len(points) // 22
    out = bytearray(48 * n)
    for b in range(12):
        out[b::48] = points[b::22]
    for b in range(4):
        out[16 + b::48] = points[12 + b::22]
    times = array.array("f", b"".join(points[i * 22 + 18:i * 22 + 22] for i in range(n)))
    stamps = array.array("d", [EPOCH + t + v for v in times]).tobytes()
    for b in range(8):
        out[24 + b::48] = stamps[b::8]
    out[32::48] = points[16::22]
    out[33::48] = points[17::22]
    if short:
        out = out[:-48]
    cdr = Cdr(big_endian)
    header(cdr, t, "PandarXT-32")
    cdr.put("I", 1)  # height
    cdr.put("I", n)  # width
    fields = [("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("intensity", 16, 7), ("timestamp", 24, 8),
              ("ring", 32, 4)]
    cdr.put("I", len(fields))
    for name, offset, datatype in fields:
        cdr.string(name)
        cdr.put("I", offset)
        cdr.put("B", datatype)
        cdr.put("I", 1)
    cdr.put("?", False)  # is_bigendian: the points are little-endian whatever the CDR is
    cdr.put("I", 48)
    cdr.put("I", 48 * n)
    cdr.blob(bytes(out))
    cdr.put("?", True)
    return cdr.bytes()


def imu(t, values, big_endian):
    ax, ay, az, gx, gy, gz = values
    cdr = Cdr(big_endian)
    header(cdr, t, "imu_sensor_frame")
    cdr.put("dddd", 0.0, 0.0, 0.0, 1.0)
    cdr.put("9d", -1.0, *([0.0] * 8))
    cdr.put("ddd", gx, gy, gz)
    cdr.put("9d", *([0.0] * 9))
    cdr.put("ddd", ax, ay, az)
    cdr.put("9d", *([0.0] * 9))
    return cdr.bytes()


def odometry(row, big_endian):
    cdr = Cdr(big_endian)
    header(cdr, row[0], "world")
    cdr.string("base_link")
    cdr.put("7d", *row[1:8])
    cdr.put("36d", *([0.0] * 36))
    cdr.put("6d", *([0.0] * 6))
    cdr.put("36d", *([0.0] * 36))
    return cdr.bytes()


def transforms(pairs, big_endian):
    cdr = Cdr(big_endian)
    cdr.put("I", len(pairs))
    for parent, child, m in pairs:
        header(cdr, 0.0, parent)
        cdr.string(child)
        cdr.put("ddd", m[0][3], m[1][3], m[2][3])
        cdr.put("dddd", *quaternion(m))
    return cdr.bytes()


def log(text, big_endian):
    cdr = Cdr(big_endian)
    cdr.put("i", EPOCH)
    cdr.put("I", 0)
    cdr.put("B", 20)
    cdr.string("hesai_ros_driver")
    cdr.string(text)
    cdr.string("driver.cpp")
    cdr.string("start")
    cdr.put("I", 42)
    return cdr.bytes()


TOPICS = [
    ("/hesai/pandar", "sensor_msgs/msg/PointCloud2"),
    ("/alphasense/imu", "sensor_msgs/msg/Imu"),
    ("/ground_truth", "nav_msgs/msg/Odometry"),
    ("/tf_static", "tf2_msgs/msg/TFMessage"),
    ("/rosout", "rcl_interfaces/msg/Log"),
]


def database(path):
    db = sqlite3.connect(path)
    db.executescript(
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
        "INSERT INTO schema VALUES (3, 'humble');"
        "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, "
        "metadata TEXT NOT NULL);"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
        "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
        "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
        "CREATE INDEX timestamp_idx ON messages (timestamp ASC);")
    for k, (name, kind) in enumerate(TOPICS):
        db.execute("INSERT INTO topics VALUES (?, ?, ?, 'cdr', '')", (k + 1, name, kind))
    return db


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dataset")
    parser.add_argument("out")
    parser.add_argument("--split", action="store_true")
    parser.add_argument("--big-endian", action="store_true")
    parser.add_argument("--no-static", action="store_true")
    parser.add_argument("--short-cloud", type=int, default=-1)
    args = parser.parse_args()
    with open(os.path.join(args.dataset, "metadata.json")) as f:
        metadata = json.load(f)
    big = args.big_endian
    messages = []  # (record time ns, topic index, data)
    if not args.no_static:
        mounts = [("base_link", "PandarXT-32", metadata["extrinsics"]["R_T_L"]["matrix"]),
                  ("base_link", "imu_sensor_frame", metadata["extrinsics"]["R_T_I"]["matrix"])]
        messages.append((to_ns(0.0), 4, transforms(mounts, big)))
    messages.append((to_ns(0.0), 5, log("lidar connected", big)))
    with open(os.path.join(args.dataset, "imu.csv")) as f:
        next(f)
        for line in f:
            values = [float(v) for v in line.split(",")]
            messages.append((to_ns(values[0] + 0.002), 2, imu(values[0], values[1:], big)))
    with open(os.path.join(args.dataset, "groundtruth.tum")) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                row = [float(v) for v in line.split()]
                messages.append((to_ns(row[0]), 3, odometry(row, big)))
    with open(os.path.join(args.dataset, "scans.tum")) as f:
        rows = [[float(v) for v in line.split()] for line in f
                if line.strip() and not line.startswith("#")]
    for k, row in enumerate(rows):
        with open(os.path.join(args.dataset, "scans", "%06d.pcd" % k), "rb") as f:
            data = f.read()
        marker = b"DATA binary\n"
        points = data[data.index(marker) + len(marker):]
        messages.append((to_ns(row[0] + 0.03), 1, cloud(row[0], points, big, k == args.short_cloud)))
    messages.sort(key=lambda m: m[0])
    if not args.split:
        db = database(args.out)
        db.executemany("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                       [(topic, t, data) for t, topic, data in messages])
        db.commit()
        db.close()
        return
    os.makedirs(args.out)
    name = os.path.basename(os.path.normpath(args.out))
    files = ["%s_0.db3" % name, "%s_1.db3" % name]
    middle = messages[len(messages) // 2][0]
    for k, file in enumerate(files):
        db = database(os.path.join(args.out, file))
        db.executemany("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                       [(topic, t, data) for t, topic, data in messages
                        if (t < middle) == (k == 0)])
        db.commit()
        db.close()
    with open(os.path.join(args.out, "metadata.yaml"), "w") as f:
        f.write("rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
                "  duration:\n    nanoseconds: %d\n  starting_time:\n"
                "    nanoseconds_since_epoch: %d\n  message_count: %d\n"
                "  relative_file_paths:\n    - %s\n    - %s\n  compression_format: \"\"\n"
                "  compression_mode: \"\"\n" % (messages[-1][0] - messages[0][0], messages[0][0],
                                               len(messages), files[0], files[1]))


if __name__ == "__main__":
    main()
