// Writes a dataset of ours as a ROS 2 robot with a Hesai PandarXT-32 would record it to MCAP, with
// npm's writers, not ours: @mcap/core (zstd chunks from @foxglove/wasm-zstd), the message
// definitions of @foxglove/rosmsg-msgs-common (Humble) and CDR from
// @foxglove/rosmsg2-serialization. For the ROS 2 import's tests (cli/tests/recording_import_test).
//
// usage: node npm_ros2_recording.js DATASET_DIR OUT.mcap NODE_MODULES_DIR
//
// DATASET_DIR must hold binary PCD scans (isg simulate --pcd binary). The recording, as a handheld
// rig's (no odometry, and no /tf_static: the import is given the mounts):
//   /hesai/pandar    sensor_msgs/msg/PointCloud2 in "PandarXT-32": x y z float32 at 0 4 8,
//                    intensity float32 at 16, timestamp float64 at 24 (each point's, seconds since
//                    the epoch), ring uint16 at 32, point_step 48; stamped at the start of its turn,
//                    logged 30 ms later.
//   /alphasense/imu  sensor_msgs/msg/Imu in "imu_sensor_frame", logged 2 ms later.
//   /ground_truth    nav_msgs/msg/Odometry world -> base_link.
//   /diagnostics     a JSON-encoded channel the import has no use for.
"use strict";
const path = require("path");
const fs = require("fs");
const fsp = require("fs/promises");

const EPOCH = 1650000000n;

function definitionsOf(all, root) {
  // The root type's definition first, then every complex type it uses, each once.
  const out = [];
  const seen = new Set();
  const visit = (name) => {
    if (seen.has(name)) return;
    seen.add(name);
    const def = all[name];
    if (!def) throw new Error("no definition of " + name);
    out.push(def);
    for (const field of def.definitions) {
      if (field.isComplex) visit(field.type);
    }
  };
  visit(root);
  return out;
}

function stampOf(t) {
  const ns = BigInt(Math.round(t * 1e9));
  const total = EPOCH * 1000000000n + ns;
  return { sec: Number(total / 1000000000n), nanosec: Number(total % 1000000000n), ns: total };
}

function readRows(file) {
  return fs.readFileSync(file, "utf8").split("\n")
    .filter((line) => line.trim() && !line.startsWith("#"))
    .map((line) => line.trim().split(/[\s,]+/).map(Number));
}

function hesaiCloud(points, t) {
  // A scan's 22-byte points (x y z intensity float32, ring uint16, time float32) as Hesai's.
  const n = points.length / 22;
  const src = new DataView(points.buffer, points.byteOffset, points.byteLength);
  const out = new DataView(new ArrayBuffer(48 * n));
  for (let i = 0; i < n; ++i) {
    const a = 22 * i, b = 48 * i;
    out.setFloat32(b, src.getFloat32(a, true), true);
    out.setFloat32(b + 4, src.getFloat32(a + 4, true), true);
    out.setFloat32(b + 8, src.getFloat32(a + 8, true), true);
    out.setFloat32(b + 16, src.getFloat32(a + 12, true), true);
    out.setFloat64(b + 24, Number(EPOCH) + t + src.getFloat32(a + 18, true), true);
    out.setUint16(b + 32, src.getUint16(a + 16, true), true);
  }
  const field = (name, offset, datatype) => ({ name, offset, datatype, count: 1 });
  const stamp = stampOf(t);
  return {
    header: { stamp: { sec: stamp.sec, nanosec: stamp.nanosec }, frame_id: "PandarXT-32" },
    height: 1, width: n,
    fields: [field("x", 0, 7), field("y", 4, 7), field("z", 8, 7), field("intensity", 16, 7),
             field("timestamp", 24, 8), field("ring", 32, 4)],
    is_bigendian: false, point_step: 48, row_step: 48 * n,
    data: new Uint8Array(out.buffer), is_dense: true,
  };
}

async function main() {
  const [dataset, out, modules] = process.argv.slice(2);
  const need = (n) => require(path.join(modules, n));
  const { McapWriter } = need("@mcap/core");
  const { FileHandleWritable } = need("@mcap/nodejs");
  const { stringify } = need("@foxglove/rosmsg");
  const { MessageWriter } = need("@foxglove/rosmsg2-serialization");
  const humble = need("@foxglove/rosmsg-msgs-common").ros2humble;
  const zstd = need("@foxglove/wasm-zstd");
  await zstd.isLoaded;

  const handle = await fsp.open(out, "w");
  const writer = new McapWriter({
    writable: new FileHandleWritable(handle),
    chunkSize: 1 << 20,
    compressChunk: (data) => ({ compression: "zstd", compressedData: zstd.compress(data) }),
  });
  await writer.start({ profile: "ros2", library: "npm @mcap/core" });
  const channels = {};
  const serializers = {};
  const channel = async (topic, type) => {
    const defs = definitionsOf(humble, type);
    const rosType = type.replace("/", "/msg/");
    const schemaId = await writer.registerSchema({
      name: rosType, encoding: "ros2msg", data: new TextEncoder().encode(stringify(defs)) });
    channels[topic] = await writer.registerChannel({
      topic, messageEncoding: "cdr", schemaId, metadata: new Map() });
    serializers[topic] = new MessageWriter(defs);
  };
  await channel("/hesai/pandar", "sensor_msgs/PointCloud2");
  await channel("/alphasense/imu", "sensor_msgs/Imu");
  await channel("/ground_truth", "nav_msgs/Odometry");
  const diagnostics = await writer.registerChannel({
    topic: "/diagnostics", messageEncoding: "json", schemaId: 0, metadata: new Map() });

  const messages = [];  // [log time ns, topic, message]
  for (const [t, ax, ay, az, gx, gy, gz] of readRows(path.join(dataset, "imu.csv")).slice(1)) {
    const s = stampOf(t);
    const zero = [0, 0, 0, 0, 0, 0, 0, 0, 0];
    messages.push([stampOf(t + 0.002).ns, "/alphasense/imu", {
      header: { stamp: { sec: s.sec, nanosec: s.nanosec }, frame_id: "imu_sensor_frame" },
      orientation: { x: 0, y: 0, z: 0, w: 1 }, orientation_covariance: [-1, 0, 0, 0, 0, 0, 0, 0, 0],
      angular_velocity: { x: gx, y: gy, z: gz }, angular_velocity_covariance: zero,
      linear_acceleration: { x: ax, y: ay, z: az }, linear_acceleration_covariance: zero }]);
  }
  for (const [t, x, y, z, qx, qy, qz, qw] of readRows(path.join(dataset, "groundtruth.tum"))) {
    const s = stampOf(t);
    messages.push([s.ns, "/ground_truth", {
      header: { stamp: { sec: s.sec, nanosec: s.nanosec }, frame_id: "world" },
      child_frame_id: "base_link",
      pose: { pose: { position: { x, y, z }, orientation: { x: qx, y: qy, z: qz, w: qw } },
              covariance: new Array(36).fill(0) },
      twist: { twist: { linear: { x: 0, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } },
               covariance: new Array(36).fill(0) } }]);
  }
  readRows(path.join(dataset, "scans.tum")).forEach((row, k) => {
    const pcd = fs.readFileSync(path.join(dataset, "scans", String(k).padStart(6, "0") + ".pcd"));
    const at = pcd.indexOf("DATA binary\n") + "DATA binary\n".length;
    messages.push([stampOf(row[0] + 0.03).ns, "/hesai/pandar", hesaiCloud(pcd.subarray(at), row[0])]);
  });
  messages.sort((a, b) => (a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : 0));
  const sequence = {};
  let diagnosticsNext = messages[0][0];
  for (const [logTime, topic, message] of messages) {
    if (logTime >= diagnosticsNext) {  // 1 Hz of something else, not ROS
      await writer.addMessage({ channelId: diagnostics, sequence: 0, logTime, publishTime: logTime,
                                data: new TextEncoder().encode('{"level": 0}') });
      diagnosticsNext += 1000000000n;
    }
    sequence[topic] = (sequence[topic] || 0) + 1;
    await writer.addMessage({ channelId: channels[topic], sequence: sequence[topic], logTime,
                              publishTime: logTime, data: serializers[topic].writeMessage(message) });
  }
  await writer.end();
  await handle.close();
}
main().catch((e) => { console.error(e); process.exit(1); });
