// A ROS 2 MCAP file written by npm's writers, not ours (@mcap/core with zstd chunks from
// @foxglove/wasm-zstd, CDR from @foxglove/rosmsg2-serialization): an oracle for the MCAP reader.
// usage: node npm_mcap_writer.js OUT.mcap NODE_MODULES_DIR   (five geometry_msgs/msg/PoseStamped on
// /pose, stamps 1700000000.25 + i s, position (i, 2i, 0.5)); run by McapReader.ReadsWhatNpmsWritersWrote.
"use strict";
const path = require("path");
const fs = require("fs/promises");
async function main() {
  const [out, modules] = process.argv.slice(2);
  const need = (n) => require(path.join(modules, n));
  const { McapWriter } = need("@mcap/core");
  const { FileHandleWritable } = need("@mcap/nodejs");
  const { parse } = need("@foxglove/rosmsg");
  const { MessageWriter } = need("@foxglove/rosmsg2-serialization");
  const zstd = need("@foxglove/wasm-zstd");
  await zstd.isLoaded;
  const handle = await fs.open(out, "w");
  const writer = new McapWriter({
    writable: new FileHandleWritable(handle),
    chunkSize: 64,
    compressChunk: (data) => ({ compression: "zstd", compressedData: zstd.compress(data) }),
  });
  await writer.start({ profile: "ros2", library: "npm @mcap/core" });
  const poseText = "std_msgs/Header header\ngeometry_msgs/Pose pose\n" +
    "================================================================================\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n" +
    "================================================================================\nMSG: geometry_msgs/Pose\nPoint position\nQuaternion orientation\n" +
    "================================================================================\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" +
    "================================================================================\nMSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n";
  const defs = parse(poseText, { ros2: true });
  const w = new MessageWriter(defs);
  const schema = await writer.registerSchema({ name: "geometry_msgs/msg/PoseStamped", encoding: "ros2msg", data: new TextEncoder().encode(poseText) });
  const channel = await writer.registerChannel({ topic: "/pose", messageEncoding: "cdr", schemaId: schema, metadata: new Map() });
  for (let i = 0; i < 5; ++i) {
    const msg = { header: { stamp: { sec: 1700000000 + i, nanosec: 250000000 }, frame_id: "map" },
                  pose: { position: { x: i, y: 2 * i, z: 0.5 }, orientation: { x: 0, y: 0, z: Math.sin(0.1 * i), w: Math.cos(0.1 * i) } } };
    const t = BigInt(1700000000 + i) * 1000000000n + 250000000n;
    await writer.addMessage({ channelId: channel, sequence: i, logTime: t, publishTime: t, data: w.writeMessage(msg) });
  }
  await writer.end();
  await handle.close();
}
main().catch((e) => { console.error(e); process.exit(1); });
