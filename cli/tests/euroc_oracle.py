#!/usr/bin/env python3
"""`isg simulate --euroc` read by independent readers: Python's csv, PyYAML and OpenCV.

Simulates 6 s of D1 (the walk starts down its corridor) with a RealSense D435 and checks the
EuRoC layout as EuRoC's readers take it: every image listed in data.csv exists and decodes with
OpenCV at the sensor's size (RGB 8-bit, depth 16-bit one channel), stamps in nanoseconds 1/30 s
apart, depth registered to cam0 (the same stamps), the IMU and ground-truth rows with EuRoC's
columns at the IMU's rate, sensor.yaml and Kalibr's camchain.yaml parsed by PyYAML and agreeing,
depth in millimetres within the sensor's range. Then the textures: OpenCV's Shi-Tomasi detector
(goodFeaturesToTrack, quality 0.01, 10 px apart) finds at least 100 corners in at least 90 % of
the frames. Run by CTest with /usr/bin/python3 (python3-opencv, python3-yaml); exits 0 when
every check passes.
"""
import argparse
import csv
import pathlib
import shutil
import statistics
import sys
import tempfile

import cv2
import yaml

from oracle_checks import check, run, verdict

SECONDS = 6
RATE = 30


def rows(path):
    with open(path, newline="") as f:
        return [r for r in csv.reader(f) if r and not r[0].startswith("#")]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--isg", required=True)
    parser.add_argument("--plans", required=True)
    args = parser.parse_args()
    work = pathlib.Path(tempfile.mkdtemp(prefix="euroc_oracle_"))
    try:
        shutil.copy(pathlib.Path(args.plans) / "d1.json", work / "d1.json")
        (work / "s.json").write_text(
            '{"format": "isg.scenario", "version": 1, "plan": "d1.json", "seed": 4,'
            ' "cameras": [{"model": "realsense-d435"}]}')
        out = work / "ds"
        run([args.isg, "simulate", str(work / "s.json"), "-o", str(out), "--duration",
             str(SECONDS), "--euroc", "-q"])
        mav0 = out / "mav0"
        cam = rows(mav0 / "cam0" / "data.csv")
        depth = rows(mav0 / "depth0" / "data.csv")
        check(len(cam) == SECONDS * RATE + 1, f"cam0 has {len(cam)} frames")
        check(cam == depth, "depth0's stamps and files are cam0's")
        stamps = [int(r[0]) for r in cam]
        steps = {b - a for a, b in zip(stamps, stamps[1:])}
        check(steps <= {33333333, 33333334}, f"frames 1/30 s apart in ns: {sorted(steps)[:4]}")
        check(stamps[0] == 1000000000 * 10**9, f"first stamp {stamps[0]}")
        counts = []
        for i, (stamp, name) in enumerate(cam):
            check(name == f"{stamp}.png", f"row {i}: file {name} named by its stamp")
            image = cv2.imread(str(mav0 / "cam0" / "data" / name), cv2.IMREAD_UNCHANGED)
            check(image is not None and image.shape == (480, 640, 3) and image.dtype == "uint8",
                  f"cam0 {name} decodes as 640x480 RGB")
            d = cv2.imread(str(mav0 / "depth0" / "data" / name), cv2.IMREAD_UNCHANGED)
            check(d is not None and d.shape == (480, 640) and d.dtype == "uint16",
                  f"depth0 {name} decodes as 640x480 16-bit")
            if d is not None:
                valid = d[d > 0]
                check(valid.size > 0.5 * d.size and valid.min() >= 280 and valid.max() <= 10000,
                      f"depth0 {name}: millimetres within 0.28-10 m")
            if image is not None and i % 3 == 0:
                grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
                corners = cv2.goodFeaturesToTrack(grey, maxCorners=2000, qualityLevel=0.01,
                                                  minDistance=10)
                counts.append(0 if corners is None else len(corners))
        enough = sum(c >= 100 for c in counts)
        print(f"corners per frame: median {statistics.median(counts)}, least {min(counts)}, "
              f"{enough} of {len(counts)} frames with 100 or more")
        check(enough >= 0.9 * len(counts), "at least 100 corners in 90 % of the frames")

        imu = rows(mav0 / "imu0" / "data.csv")
        states = rows(mav0 / "state_groundtruth_estimate0" / "data.csv")
        check(len(imu) == SECONDS * 200 + 1 and all(len(r) == 7 for r in imu),
              f"imu0: {len(imu)} rows of 7")
        check(len(states) == len(imu) and all(len(r) == 17 for r in states),
              f"ground truth: {len(states)} rows of 17")
        check([r[0] for r in states] == [r[0] for r in imu], "ground truth at the IMU's stamps")
        cam_yaml = yaml.safe_load((mav0 / "cam0" / "sensor.yaml").read_text())
        imu_yaml = yaml.safe_load((mav0 / "imu0" / "sensor.yaml").read_text())
        chain = yaml.safe_load((mav0 / "camchain.yaml").read_text())
        check(cam_yaml["sensor_type"] == "camera" and cam_yaml["resolution"] == [640, 480],
              "cam0 sensor.yaml: a 640x480 camera")
        check(len(cam_yaml["T_BS"]["data"]) == 16, "cam0 T_BS is 4x4")
        check(imu_yaml["sensor_type"] == "imu" and imu_yaml["rate_hz"] == 200, "imu0 at 200 Hz")
        check(chain["cam0"]["intrinsics"] == cam_yaml["intrinsics"],
              "camchain's intrinsics are sensor.yaml's")
        check(abs(cam_yaml["intrinsics"][0] - 620.8) < 0.1, "the D435's focal length")
        tum = [l for l in (mav0 / "cam0.tum").read_text().splitlines() if not l.startswith("#")]
        check(len(tum) == len(cam), "cam0.tum: a pose per frame")
        # Stamped as the images are, as the floor-plan benchmark gives its ground truth: the
        # seconds with nine decimals are the frame's nanoseconds.
        check([l.split()[0].replace(".", "") for l in tum] == [r[0] for r in cam],
              "cam0.tum's stamps are the images' (seconds, to the nanosecond)")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
