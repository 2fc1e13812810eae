#!/usr/bin/env python3
"""Camera frames in `isg simulate --euroc --rosbag/--mcap` read by independent readers.

Two short simulations: a RealSense D435 on the legged base through D1 (its corridor), and the
floor-plan benchmark's 360° rig (insta360-one-rs) carried by hand through D1. Each writes its
EuRoC folder and a ROS 1 bag (--format rosbag: read with Debian's python3-rosbag) or an MCAP file
(--format mcap: read with npm's @mcap/core and @foxglove/rosmsg2-serialization through
mcap_oracle.js). For every camera folder under mav0 the bag must have:
  /<name>/image_raw/compressed (sensor_msgs/CompressedImage) and /<name>/camera_info
  (sensor_msgs/CameraInfo), one of each per row of data.csv, stamped with its EuRoC stamp, in
  the camera's frame; RGB frames as JPEG that OpenCV decodes at the sensor's size within 3 grey
  levels (mean) of the PNG; depth frames as the very 16-bit PNG, decoding to the same millimetres;
  CameraInfo's size, K, P and distortion (plumb_bob zeros for the D435, equidistant k1-k4 for the
  rig's lenses) equal to sensor.yaml; the camera's mount on /tf_static equal to the IMU's mount
  times sensor.yaml's T_BS. The rig's IMU on /imu/data at 1000 Hz. OpenCV's Shi-Tomasi detector
  (goodFeaturesToTrack, quality 0.01, 10 px apart) finds in the D435's JPEG frames at least 90 %
  of the corners it finds in the PNG frames (70 % in every frame): the compression keeps what a
  visual odometry tracks.
Run by CTest with /usr/bin/python3 (python3-opencv, python3-yaml, python3-rosbag). Exit 77
(skipped) for --format mcap when node or the npm oracles are not installed (ci/install-deps).
usage: camera_bag_oracle.py --isg ISG --plans DIR --format rosbag|mcap [--oracles NODE_MODULES]
"""
import argparse
import base64
import csv
import json
import os
import pathlib
import shutil
import sys
import tempfile

import cv2
import numpy as np
import yaml

from oracle_checks import check, read_mcap_with_npm, run, verdict

MCAP_MODULES = ["@mcap/core", "@mcap/nodejs", "@foxglove/rosmsg",
                "@foxglove/rosmsg2-serialization", "@foxglove/crc", "@foxglove/wasm-zstd"]
IMAGE_TYPE = {"rosbag": "sensor_msgs/CompressedImage", "mcap": "sensor_msgs/msg/CompressedImage"}
INFO_TYPE = {"rosbag": "sensor_msgs/CameraInfo", "mcap": "sensor_msgs/msg/CameraInfo"}


def rows(path):
    with open(path, newline="") as f:
        return [r for r in csv.reader(f) if r and not r[0].startswith("#")]


def matrix_of(translation, quaternion):
    """A 4x4 transform from a translation and an (x, y, z, w) quaternion."""
    x, y, z, w = quaternion
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    out = np.eye(4)
    out[:3, :3] = rotation
    out[:3, 3] = translation
    return out


def read_rosbag(path):
    """Topics → (type, messages as plain dicts), read with python3-rosbag."""
    import rosbag
    out = {}
    with rosbag.Bag(str(path)) as bag:
        types = {t: v.msg_type for t, v in bag.get_type_and_topic_info().topics.items()}
        for topic, m, _ in bag.read_messages():
            out.setdefault(topic, (types[topic], []))
            if topic == "/tf_static":
                out[topic][1].extend({
                    "parent": t.header.frame_id, "child": t.child_frame_id,
                    "translation": [t.transform.translation.x, t.transform.translation.y,
                                    t.transform.translation.z],
                    "rotation": [t.transform.rotation.x, t.transform.rotation.y,
                                 t.transform.rotation.z, t.transform.rotation.w]}
                    for t in m.transforms)
            elif types[topic] == IMAGE_TYPE["rosbag"]:
                out[topic][1].append({"stamp": m.header.stamp.to_nsec(),
                                      "frame": m.header.frame_id, "format": m.format,
                                      "data": bytes(m.data)})
            elif types[topic] == INFO_TYPE["rosbag"]:
                out[topic][1].append({"stamp": m.header.stamp.to_nsec(),
                                      "frame": m.header.frame_id, "width": m.width,
                                      "height": m.height, "model": m.distortion_model,
                                      "d": list(m.D), "k": list(m.K), "p": list(m.P)})
            else:
                out[topic][1].append(None)
    return out


def read_mcap(path, oracles):
    """The same from an MCAP file, through the npm readers (mcap_oracle.js)."""
    got = read_mcap_with_npm(path, oracles)
    out = {}
    for topic, channel in got["channels"].items():
        messages = got["messages"][topic]
        kind = channel["type"]
        if topic == "/tf_static":
            messages = [t for m in messages for t in m]
        elif kind == IMAGE_TYPE["mcap"]:
            messages = [{"stamp": m["stamp"][0] * 10**9 + m["stamp"][1], "frame": m["frame"],
                         "format": m["format"], "data": base64.b64decode(m["data_base64"])}
                        for m in messages]
        elif kind == INFO_TYPE["mcap"]:
            messages = [{"stamp": m["stamp"][0] * 10**9 + m["stamp"][1], "frame": m["frame"],
                         "width": m["width"], "height": m["height"],
                         "model": m["distortion_model"], "d": m["d"], "k": m["k"], "p": m["p"]}
                        for m in messages]
        out[topic] = (kind, messages)
    return out


def corner_count(image):
    found = cv2.goodFeaturesToTrack(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY), maxCorners=2000,
                                    qualityLevel=0.01, minDistance=10)
    return 0 if found is None else len(found)


def check_rgb(name, message, png_path, size, corners):
    check(message["format"] == "rgb8; jpeg compressed bgr8", f"{name}: format {message['format']}")
    check(message["data"][:2] == b"\xff\xd8", f"{name}: JPEG data")
    image = cv2.imdecode(np.frombuffer(message["data"], np.uint8), cv2.IMREAD_UNCHANGED)
    if image is None or image.shape != (size[1], size[0], 3):
        check(False, f"{name}: JPEG decodes at {size[0]}x{size[1]} RGB")
        return
    png = cv2.imread(str(png_path), cv2.IMREAD_UNCHANGED)
    error = float(np.mean(np.abs(image.astype(float) - png.astype(float))))
    check(error < 3.0, f"{name}: JPEG within 3 grey levels of the PNG (mean {error:.2f})")
    if corners is not None:
        corners.append((corner_count(image), corner_count(png)))


def check_depth(name, message, png_path):
    check(message["format"] == "16UC1; png compressed ", f"{name}: format {message['format']}")
    image = cv2.imdecode(np.frombuffer(message["data"], np.uint8), cv2.IMREAD_UNCHANGED)
    png = cv2.imread(str(png_path), cv2.IMREAD_UNCHANGED)
    check(image is not None and image.dtype == np.uint16 and np.array_equal(image, png),
          f"{name}: the depth PNG's millimetres, every pixel")


def check_info(name, info, sensor):
    fx, fy, cx, cy = sensor["intrinsics"]
    coefficients = sensor["distortion_coefficients"]
    if sensor["distortion_model"] == "equidistant":
        model = ("equidistant", coefficients)
    else:
        model = ("plumb_bob", coefficients + [0.0])
    check([info["width"], info["height"]] == sensor["resolution"], f"{name}: size {info}")
    check(np.allclose(info["k"], [fx, 0, cx, 0, fy, cy, 0, 0, 1], rtol=0, atol=1e-9),
          f"{name}: K {info['k']}")
    check(np.allclose(info["p"], [fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0], rtol=0, atol=1e-9),
          f"{name}: P {info['p']}")
    check((info["model"], len(info["d"])) == (model[0], len(model[1]))
          and np.allclose(info["d"], model[1], rtol=0, atol=1e-12),
          f"{name}: distortion {info['model']} {info['d']}")


def check_camera(topics, kind, mav0, name, corners, mounts):
    folder = mav0 / name
    sensor = yaml.safe_load((folder / "sensor.yaml").read_text())
    frames = rows(folder / "data.csv")
    image_topic, info_topic = f"/{name}/image_raw/compressed", f"/{name}/camera_info"
    check(topics.get(image_topic, ("",))[0] == IMAGE_TYPE[kind], f"{image_topic}'s type")
    check(topics.get(info_topic, ("",))[0] == INFO_TYPE[kind], f"{info_topic}'s type")
    images, infos = topics[image_topic][1], topics[info_topic][1]
    check(len(images) == len(frames) == len(infos),
          f"{name}: {len(images)} images, {len(infos)} infos for {len(frames)} frames")
    depth = "depth_scale_m" in sensor
    for i, ((stamp, file), image, info) in enumerate(zip(frames, images, infos)):
        where = f"{name} frame {i}"
        check(image["stamp"] == int(stamp) == info["stamp"], f"{where}: stamped {stamp}")
        check(image["frame"] == name == info["frame"], f"{where}: frame {image['frame']}")
        if depth:
            check_depth(where, image, folder / "data" / file)
        else:
            check_rgb(where, image, folder / "data" / file, sensor["resolution"], corners)
        check_info(where, info, sensor)
    # The mount: base_link → name is base_link → imu times EuRoC's T_BS (the camera in the
    # IMU's frame).
    T_BS = np.array(sensor["T_BS"]["data"]).reshape(4, 4)
    check(name in mounts and "imu" in mounts, f"{name} and imu on /tf_static")
    if name in mounts and "imu" in mounts:
        check(np.allclose(mounts[name], mounts["imu"] @ T_BS, rtol=0, atol=1e-9),
              f"{name}'s mount is the IMU's times T_BS")
    return len(frames)


def simulate(isg, work, scenario, seconds, kind):
    (work / "s.json").write_text(json.dumps(scenario))
    out = work / "ds"
    record = work / ("ds.bag" if kind == "rosbag" else "ds.mcap")
    run([isg, "simulate", str(work / "s.json"), "-o", str(out), "--duration", str(seconds),
         "--euroc", "--" + kind, str(record), "-q", "--force"])
    return out / "mav0", record


def read(kind, record, oracles):
    return read_rosbag(record) if kind == "rosbag" else read_mcap(record, oracles)


def check_run(args, work, scenario, seconds, cameras, corners):
    mav0, record = simulate(args.isg, work, scenario, seconds, args.format)
    topics = read(args.format, record, args.oracles)
    mounts = {t["child"]: matrix_of(t["translation"], t["rotation"])
              for t in topics["/tf_static"][1] if t["parent"] == "base_link"}
    names = sorted(p.name for p in mav0.iterdir() if (p / "sensor.yaml").exists()
                   and yaml.safe_load((p / "sensor.yaml").read_text())["sensor_type"] == "camera")
    check(names == cameras, f"camera folders {names}")
    for name in names:
        count = check_camera(topics, args.format, mav0, name, corners, mounts)
        print(f"{record.name}: {name}, {count} frames")
    return topics


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--isg", required=True)
    parser.add_argument("--plans", required=True)
    parser.add_argument("--format", choices=["rosbag", "mcap"], required=True)
    parser.add_argument("--oracles", default="", help="ci/oracles/node_modules (for mcap)")
    args = parser.parse_args()
    if args.format == "mcap" and (shutil.which("node") is None or not all(
            os.path.isdir(os.path.join(args.oracles, m)) for m in MCAP_MODULES)):
        print("skipped: node or the npm oracles are not installed (ci/install-deps)")
        return 77
    work = pathlib.Path(tempfile.mkdtemp(prefix="camera_bag_oracle_"))
    try:
        shutil.copy(pathlib.Path(args.plans) / "d1.json", work / "d1.json")
        base = {"format": "isg.scenario", "version": 1, "plan": "d1.json", "seed": 3}
        corners = []
        check_run(args, work, dict(base, cameras=[{"model": "realsense-d435"}]), 2,
                  ["cam0", "depth0"], corners)
        jpeg, png = sum(c[0] for c in corners), sum(c[1] for c in corners)
        worst = min(c[0] / max(c[1], 1) for c in corners)
        print(f"corners in the JPEG frames: {jpeg} against {png} in the PNG frames, the worst "
              f"frame keeps {worst:.2f}")
        check(jpeg >= 0.9 * png and worst >= 0.7,
              "the JPEG frames keep 90 % of the PNG frames' corners (70 % in every frame)")

        rig = dict(base, robot={"carrier": "handheld"}, cameras=[{"model": "insta360-one-rs"}])
        topics = check_run(args, work, rig, 0.2, ["cam0", "cam1"], None)
        imu = topics.get("/imu/data", ("", []))[1]
        check(len(imu) == 201, f"the rig's IMU: {len(imu)} samples in 0.2 s (1000 Hz)")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
