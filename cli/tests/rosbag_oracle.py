#!/usr/bin/env python3
"""A bag from `isg export` read by Debian's python3-rosbag, the reference reader of ROS 1 bags.

Simulates D1 as built (uncompressed PCD, so that this script can read the scans itself), exports
it, and checks with rosbag.Bag: every topic with its type and a message count equal to the
dataset's; the PointCloud2 layout of the Velodyne driver (x y z intensity float32, ring uint16,
time float32 seconds, point_step 22); sampled clouds, IMU samples, odometry and ground-truth poses
equal to the dataset's values; the static transforms equal to metadata.json's mounts; the
metadata carried on /isg/metadata equal to metadata.json (but its PCD encoding). Then checks
that a compressed dataset of the same seed gives the very same bag, byte for byte.
Run by CTest with /usr/bin/python3 (python3-rosbag); exits 0 when every check passes.
"""
import argparse
import json
import pathlib
import struct
import sys
import tempfile

import rosbag

from oracle_checks import check, run, verdict

OFFSET = 1000000000  # isg export's default --stamp-offset, whole seconds


def tum(path):
    rows = []
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            rows.append([float(x) for x in line.split()])
    return rows


def imu_rows(path):
    lines = path.read_text().splitlines()
    assert lines[0] == "t,ax,ay,az,gx,gy,gz", lines[0]
    return [[float(x) for x in line.split(",")] for line in lines[1:] if line]


def pcd_binary(path):
    data = path.read_bytes()
    header_end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
    body = data[header_end:]
    return [struct.unpack_from("<ffffHf", body, i) for i in range(0, len(body), 22)]


def same_stamp(stamp, t):
    """The header stamp is the dataset time plus the offset, to the nanosecond."""
    return (stamp.secs - OFFSET) * 1000000000 + stamp.nsecs == round(t * 1e9)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--isg", required=True)
    parser.add_argument("--duration", help="seconds of the route (default: all of it)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        duration = ["--duration", args.duration] if args.duration else []
        run([args.isg, "simulate", "builtin:d1.asbuilt", "-o", str(tmp / "ds"), "--pcd", "binary",
             "-q"] + duration)
        out = run([args.isg, "export", str(tmp / "ds"), "--rosbag", str(tmp / "d1.bag"), "-q"])
        check("wrote" in out and "/velodyne_points" in out, f"export summary: {out}")
        ds = tmp / "ds"
        gt, odom = tum(ds / "groundtruth.tum"), tum(ds / "odometry.tum")
        scans, imu = tum(ds / "scans.tum"), imu_rows(ds / "imu.csv")
        meta = json.loads((ds / "metadata.json").read_text())

        bag = rosbag.Bag(str(tmp / "d1.bag"))
        info = bag.get_type_and_topic_info()
        expected = {
            "/velodyne_points": ("sensor_msgs/PointCloud2", len(scans)),
            "/imu/data": ("sensor_msgs/Imu", len(imu)),
            "/odom": ("nav_msgs/Odometry", len(odom)),
            "/tf": ("tf2_msgs/TFMessage", len(odom)),
            "/tf_static": ("tf2_msgs/TFMessage", 1),
            "/ground_truth": ("nav_msgs/Odometry", len(gt)),
            "/isg/metadata": ("std_msgs/String", 1),
        }
        check(set(info.topics) == set(expected), f"topics {sorted(info.topics)}")
        for topic, (kind, count) in expected.items():
            got = info.topics.get(topic)
            check(got is not None and got.msg_type == kind, f"{topic} type {got}")
            check(got is not None and got.message_count == count,
                  f"{topic}: {got.message_count if got else None} messages, dataset has {count}")

        clouds = {}
        imus, odoms, gts = [], [], []
        last = 0.0
        for topic, msg, t in bag.read_messages():
            check(t.to_sec() >= last - 1e-9, f"bag time goes back at {topic}")
            last = t.to_sec()
            if topic == "/velodyne_points":
                clouds[msg.header.seq] = msg
            elif topic == "/imu/data":
                imus.append(msg)
            elif topic == "/odom":
                odoms.append(msg)
            elif topic == "/ground_truth":
                gts.append(msg)
            elif topic == "/tf_static":
                static = msg
            elif topic == "/isg/metadata":
                carried = json.loads(msg.data)

        # The metadata the bag carries is the dataset's, but for its PCD encoding.
        made = json.loads((ds / "metadata.json").read_text())
        del made["lidar"]["pcd_data"]
        check(carried == made, "/isg/metadata differs from metadata.json")
        check(carried["lidar"]["stamp"] == "first_firing" and carried["lidar"]["cut"] == "angle",
              f"conventions carried: {carried['lidar'].get('stamp')} {carried['lidar'].get('cut')}")

        # The Velodyne driver's PointCloud2 layout.
        cloud = clouds[7]
        fields = [(f.name, f.offset, f.datatype, f.count) for f in cloud.fields]
        check(fields == [("x", 0, 7, 1), ("y", 4, 7, 1), ("z", 8, 7, 1), ("intensity", 12, 7, 1),
                         ("ring", 16, 4, 1), ("time", 18, 7, 1)], f"fields {fields}")
        check(cloud.point_step == 22 and cloud.height == 1 and not cloud.is_bigendian,
              f"point_step {cloud.point_step} height {cloud.height}")
        check(cloud.header.frame_id == "velodyne", f"cloud frame {cloud.header.frame_id}")
        for k in (0, 7, len(scans) - 1):
            points = pcd_binary(ds / "scans" / f"{k:06d}.pcd")
            msg = clouds[k]
            check(msg.width == len(points), f"scan {k}: {msg.width} points, PCD {len(points)}")
            check(same_stamp(msg.header.stamp, scans[k][0]), f"scan {k} stamp {msg.header.stamp}")
            for i in (0, len(points) // 2, len(points) - 1):
                got = struct.unpack_from("<ffffHf", msg.data, i * 22)
                check(got == points[i], f"scan {k} point {i}: {got} vs {points[i]}")
            rings = {struct.unpack_from("<H", msg.data, i * 22 + 16)[0] for i in range(msg.width)}
            check(rings == set(range(16)), f"scan {k} rings {sorted(rings)}")

        for i in (0, len(imu) // 3, len(imu) - 1):
            m, row = imus[i], imu[i]
            check(same_stamp(m.header.stamp, row[0]), f"imu {i} stamp")
            got = [m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z,
                   m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z]
            check(got == row[1:], f"imu {i}: {got} vs {row[1:]}")
            check(m.orientation_covariance[0] == -1.0 and m.header.frame_id == "imu",
                  "imu without orientation, frame imu")

        def pose_of(msg):
            p, q = msg.pose.pose.position, msg.pose.pose.orientation
            return [p.x, p.y, p.z, q.x, q.y, q.z, q.w]

        for name, msgs, rows, frame in (("odom", odoms, odom, "odom"),
                                        ("ground truth", gts, gt, "plan")):
            for i in (0, len(rows) // 2, len(rows) - 1):
                check(same_stamp(msgs[i].header.stamp, rows[i][0]), f"{name} {i} stamp")
                got = pose_of(msgs[i])
                check(all(abs(a - b) < 1e-9 for a, b in zip(got, rows[i][1:])),
                      f"{name} {i}: {got} vs {rows[i][1:]}")
                check(msgs[i].header.frame_id == frame and msgs[i].child_frame_id == "base_link",
                      f"{name} frames {msgs[i].header.frame_id} -> {msgs[i].child_frame_id}")

        mounts = {t.child_frame_id: t for t in static.transforms}
        check(set(mounts) == {"velodyne", "imu"}, f"static children {sorted(mounts)}")
        for child, key in (("velodyne", "R_T_L"), ("imu", "R_T_I")):
            matrix = meta["extrinsics"][key]["matrix"]
            tr = mounts[child].transform.translation
            check(mounts[child].header.frame_id == "base_link", f"{child} parent")
            check(all(abs(a - b) < 1e-12 for a, b in
                      zip([tr.x, tr.y, tr.z], [matrix[0][3], matrix[1][3], matrix[2][3]])),
                  f"{child} translation")
        bag.close()

        # The compressed dataset of the same seed holds the same points: the same bag.
        run([args.isg, "simulate", "builtin:d1.asbuilt", "-o", str(tmp / "dsc"), "-q", "--rosbag",
             str(tmp / "d1c.bag")] + duration)
        check((tmp / "d1.bag").read_bytes() == (tmp / "d1c.bag").read_bytes(),
              "bags of a binary and a compressed dataset of one seed differ")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
