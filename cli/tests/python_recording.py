#!/usr/bin/python3
"""Writes a dataset of ours as another robot's recording would be, with Debian's python3-rosbag
(another writer than ours): the import test's recordings from elsewhere.

usage: python_recording.py DATASET_DIR OUT.bag velodyne|ouster [--extra-cloud-topic]
                           [--short-cloud K] [--imu-in-g] [--odometry-on-tf]

DATASET_DIR must hold binary PCD scans (isg simulate --pcd binary). The layouts:

velodyne  The ROS 1 velodyne_pointcloud driver's conventions: /velodyne_points in frame
          "velodyne", PointXYZIRT (x y z at 0 4 8, intensity float32 at 16, ring uint16 at 20, time
          float32 at 24, point_step 32), each cloud stamped at the end of its turn (every `time`
          negative), a few NaN points (no return, is_dense false); /imu/data in "imu_link";
          /odometry/filtered (nav_msgs/Odometry odom -> base_link); the mounts on /tf_static; the
          ground truth as geometry_msgs/PoseStamped on /vicon/base_link. bz2 chunks. Messages are
          recorded 20 ms after their stamps (the clouds 35 ms), as a recorder receives them.
ouster    ouster_ros's conventions: /os_cloud_node/points in "os_sensor", x y z at 0 4 8,
          intensity float32 at 16, t uint32 nanoseconds at 20, reflectivity uint16 at 24, ring
          uint8 at 26, ambient uint16 at 28, range uint32 at 32, point_step 48, stamped at the
          start of the turn, empty pixels as zero points; /os_cloud_node/imu in "os_imu"; /odom;
          /ground_truth (nav_msgs/Odometry); no /tf_static (the import is given the mounts).
          lz4 chunks.

--extra-cloud-topic  a second PointCloud2 topic (/points_filtered): the LiDAR topic is ambiguous.
--short-cloud K      cloud K's data is one point shorter than its width says.
--imu-in-g           the IMU's specific force in g, as some drivers give it.
--odometry-on-tf     (velodyne) the odometry as a navigation stack's /tf instead of a topic:
                     odom -> base_footprint moving, base_footprint -> base_link fixed (0.35 m
                     up, on /tf_static), a localizer's map -> odom at 2 Hz, an arm joint
                     base_link -> arm_link at 10 Hz, and the IMU's mount repeated on /tf at
                     10 Hz (as ROS 1's first tf did) instead of /tf_static; several transforms
                     share a message.
"""
import argparse
import array
import json
import math
import os
import struct

import rosbag
import rospy
from geometry_msgs.msg import PoseStamped, TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, PointCloud2, PointField
from tf2_msgs.msg import TFMessage

from rotation_text import quaternion

EPOCH = 1600000000  # recordings are stamped in real time: 2020-09-13


def stamp(t):
    return rospy.Time(EPOCH) + rospy.Duration.from_sec(t)


def read_tum(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                rows.append([float(v) for v in line.split()])
    return rows


def read_points(path):
    """The 22-byte points of a binary PCD (x y z intensity float32, ring uint16, time float32)."""
    with open(path, "rb") as f:
        data = f.read()
    marker = b"DATA binary\n"
    at = data.index(marker) + len(marker)
    return data[at:]


def column(points, offset, size, n):
    out = bytearray(size * n)
    for b in range(size):
        out[b::size] = points[offset + b::22]
    return out


def cloud_message(seq, when, frame, fields, point_step, data):
    """An unorganised little-endian cloud of `data`, with no-return points (not dense)."""
    cloud = PointCloud2()
    cloud.header.seq = seq
    cloud.header.stamp = when
    cloud.header.frame_id = frame
    cloud.height, cloud.width = 1, len(data) // point_step
    cloud.fields = fields
    cloud.is_bigendian = False
    cloud.point_step, cloud.row_step = point_step, len(data)
    cloud.data = bytes(data)
    cloud.is_dense = False
    return cloud


def velodyne_cloud(points, t, seq, period):
    n = len(points) // 22
    nan_points = n // 1000
    out = bytearray(32 * (n + nan_points))
    for b in range(16):  # x y z intensity
        out[(0 if b < 12 else 4) + b:32 * n:32] = points[b::22]
    out[20:32 * n:32] = points[16::22]
    out[21:32 * n:32] = points[17::22]
    times = array.array("f", bytes(column(points, 18, 4, n)))
    times = array.array("f", [v - period for v in times])  # stamped at the end of the turn
    time_bytes = times.tobytes()
    for b in range(4):
        out[24 + b:32 * n:32] = time_bytes[b::4]
    nan = struct.pack("<fff", float("nan"), float("nan"), float("nan"))
    for i in range(nan_points):
        out[32 * (n + i):32 * (n + i) + 12] = nan
    return cloud_message(seq, stamp(t + period), "velodyne", [
        PointField("x", 0, PointField.FLOAT32, 1),
        PointField("y", 4, PointField.FLOAT32, 1),
        PointField("z", 8, PointField.FLOAT32, 1),
        PointField("intensity", 16, PointField.FLOAT32, 1),
        PointField("ring", 20, PointField.UINT16, 1),
        PointField("time", 24, PointField.FLOAT32, 1)], 32, out)


def ouster_cloud(points, t, seq):
    n = len(points) // 22
    empty = n // 500
    out = bytearray(48 * (n + empty))
    for b in range(16):
        out[(0 if b < 12 else 4) + b:48 * n:48] = points[b::22]
    times = array.array("f", bytes(column(points, 18, 4, n)))
    ns = array.array("I", [max(0, int(round(v * 1e9))) for v in times]).tobytes()
    rings = array.array("H", bytes(column(points, 16, 2, n)))
    ring8 = bytes(min(255, r) for r in rings)
    for b in range(4):
        out[20 + b:48 * n:48] = ns[b::4]
    out[26:48 * n:48] = ring8
    return cloud_message(seq, stamp(t), "os_sensor", [
        PointField("x", 0, PointField.FLOAT32, 1),
        PointField("y", 4, PointField.FLOAT32, 1),
        PointField("z", 8, PointField.FLOAT32, 1),
        PointField("intensity", 16, PointField.FLOAT32, 1),
        PointField("t", 20, PointField.UINT32, 1),
        PointField("reflectivity", 24, PointField.UINT16, 1),
        PointField("ring", 26, PointField.UINT8, 1),
        PointField("ambient", 28, PointField.UINT16, 1),
        PointField("range", 32, PointField.UINT32, 1)], 48, out)


def pose_fields(row, target):
    target.position.x, target.position.y, target.position.z = row[1:4]
    (target.orientation.x, target.orientation.y, target.orientation.z,
     target.orientation.w) = row[4:8]


def odometry(row, frame, child, seq):
    message = Odometry()
    message.header.seq = seq
    message.header.stamp = stamp(row[0])
    message.header.frame_id = frame
    message.child_frame_id = child
    pose_fields(row, message.pose.pose)
    return message


def compose(a, b):
    """Product of two 4x4 rigid transforms given as row lists."""
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


def matrix_of(row):
    """The 4x4 pose of a TUM row (t x y z qx qy qz qw)."""
    x, y, z, w = row[4:8]
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), row[1]],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), row[2]],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), row[3]],
            [0.0, 0.0, 0.0, 1.0]]


def yaw_about_z(angle, x=0.0, y=0.0, z=0.0):
    c, s = math.cos(angle), math.sin(angle)
    return [[c, -s, 0.0, x], [s, c, 0.0, y], [0.0, 0.0, 1.0, z], [0.0, 0.0, 0.0, 1.0]]


FOOTPRINT_T_BASE = yaw_about_z(0.0, z=0.35)
BASE_T_FOOTPRINT = yaw_about_z(0.0, z=-0.35)


def mount(parent, child, matrix, t):
    transform = TransformStamped()
    transform.header.stamp = stamp(t)
    transform.header.frame_id = parent
    transform.child_frame_id = child
    transform.transform.translation.x = matrix[0][3]
    transform.transform.translation.y = matrix[1][3]
    transform.transform.translation.z = matrix[2][3]
    (transform.transform.rotation.x, transform.transform.rotation.y,
     transform.transform.rotation.z, transform.transform.rotation.w) = quaternion(matrix)
    return transform


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dataset")
    parser.add_argument("out")
    parser.add_argument("layout", choices=["velodyne", "ouster"])
    parser.add_argument("--extra-cloud-topic", action="store_true")
    parser.add_argument("--short-cloud", type=int, default=-1)
    parser.add_argument("--imu-in-g", action="store_true")
    parser.add_argument("--odometry-on-tf", action="store_true")
    args = parser.parse_args()
    with open(os.path.join(args.dataset, "metadata.json")) as f:
        metadata = json.load(f)
    period = metadata["lidar"]["scan_period_s"]
    velodyne = args.layout == "velodyne"
    names = {
        "cloud": "/velodyne_points" if velodyne else "/os_cloud_node/points",
        "imu": "/imu/data" if velodyne else "/os_cloud_node/imu",
        "imu_frame": "imu_link" if velodyne else "os_imu",
        "odom": "/odometry/filtered" if velodyne else "/odom",
        "truth": "/vicon/base_link" if velodyne else "/ground_truth",
    }
    delay = rospy.Duration.from_sec(0.02)
    with rosbag.Bag(args.out, "w", compression="bz2" if velodyne else "lz4") as bag:
        if velodyne:
            mounts = TFMessage()
            mounts.transforms = [
                mount("base_link", "velodyne", metadata["extrinsics"]["R_T_L"]["matrix"], 0.0)]
            if args.odometry_on_tf:
                mounts.transforms.append(mount("base_footprint", "base_link", FOOTPRINT_T_BASE, 0.0))
            else:
                mounts.transforms.append(
                    mount("base_link", "imu_link", metadata["extrinsics"]["R_T_I"]["matrix"], 0.0))
            bag.write("/tf_static", mounts, stamp(0.0))
        with open(os.path.join(args.dataset, "imu.csv")) as f:
            next(f)
            for seq, line in enumerate(f):
                t, ax, ay, az, gx, gy, gz = (float(v) for v in line.split(","))
                scale = 1.0 / 9.80665 if args.imu_in_g else 1.0
                message = Imu()
                message.header.seq = seq
                message.header.stamp = stamp(t)
                message.header.frame_id = names["imu_frame"]
                message.orientation_covariance[0] = -1.0
                message.angular_velocity.x, message.angular_velocity.y = gx, gy
                message.angular_velocity.z = gz
                message.linear_acceleration.x = ax * scale
                message.linear_acceleration.y = ay * scale
                message.linear_acceleration.z = az * scale
                bag.write(names["imu"], message, stamp(t) + delay)
        odometry_rows = read_tum(os.path.join(args.dataset, "odometry.tum"))
        if velodyne and args.odometry_on_tf:
            arm_next, map_next = 0.0, 0.0
            for row in odometry_rows:
                transforms = [mount("odom", "base_footprint",
                                    compose(matrix_of(row), BASE_T_FOOTPRINT), row[0])]
                if row[0] >= arm_next:  # a joint that moves, beside the chain
                    transforms.append(mount("base_link", "arm_link",
                                            yaw_about_z(math.sin(row[0]), x=0.2), row[0]))
                    transforms.append(mount("base_link", "imu_link",
                                            metadata["extrinsics"]["R_T_I"]["matrix"], row[0]))
                    arm_next += 0.1
                if row[0] >= map_next:  # a localizer's correction, above the odometry's frame
                    transforms.append(mount("map", "odom",
                                            yaw_about_z(0.01 * row[0], x=0.05 * row[0]), row[0]))
                    map_next += 0.5
                message = TFMessage()
                message.transforms = transforms
                bag.write("/tf", message, stamp(row[0]) + delay)
        else:
            for seq, row in enumerate(odometry_rows):
                bag.write(names["odom"], odometry(row, "odom", "base_link", seq),
                          stamp(row[0]) + delay)
        for seq, row in enumerate(read_tum(os.path.join(args.dataset, "groundtruth.tum"))):
            if velodyne:
                message = PoseStamped()
                message.header.seq = seq
                message.header.stamp = stamp(row[0])
                message.header.frame_id = "world"
                pose_fields(row, message.pose)
            else:
                message = odometry(row, "world", "base_link", seq)
            bag.write(names["truth"], message, stamp(row[0]) + delay)
        scans = read_tum(os.path.join(args.dataset, "scans.tum"))
        for seq, row in enumerate(scans):
            points = read_points(os.path.join(args.dataset, "scans", "%06d.pcd" % seq))
            cloud = velodyne_cloud(points, row[0], seq, period) if velodyne else ouster_cloud(
                points, row[0], seq)
            if seq == args.short_cloud:
                cloud.data = cloud.data[:-cloud.point_step]
            bag.write(names["cloud"], cloud, cloud.header.stamp + rospy.Duration.from_sec(0.035))
            if args.extra_cloud_topic and seq == 0:
                bag.write("/points_filtered", cloud, cloud.header.stamp)


if __name__ == "__main__":
    main()
