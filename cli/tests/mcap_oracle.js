// Reads an MCAP file with the reference readers from npm (ci/oracles, pinned): @mcap/core's
// indexed reader (summary, chunk indexes, message indexes, chunk CRCs) and stream reader (every
// record in file order), @foxglove/rosmsg's ros2msg parser and @foxglove/rosmsg2-serialization's
// CDR reader. Prints one JSON document: the header, statistics, schemas, channels, whether the
// data section's CRC and the stream reader agree, and every message decoded (a cloud's point
// bytes as their SHA-256, an image's bytes in base64).
// usage: node mcap_oracle.js FILE.mcap NODE_MODULES_DIR
"use strict";
const path = require("path");
const fs = require("fs/promises");
const crypto = require("crypto");

const [file, modules] = process.argv.slice(2);
const need = (name) => require(path.join(modules, name));
const { McapStreamReader } = need("@mcap/core");
const { openIndexedMcap } = require("./mcap_open.js");
const { parse } = need("@foxglove/rosmsg");
const { MessageReader } = need("@foxglove/rosmsg2-serialization");
const { crc32 } = need("@foxglove/crc");

function stampOf(header) {
  return [header.stamp.sec, header.stamp.nanosec];
}

// The values a test compares, by message type.
function summarise(type, m) {
  switch (type) {
    case "sensor_msgs/msg/PointCloud2":
      return {
        stamp: stampOf(m.header),
        frame: m.header.frame_id,
        height: m.height,
        width: m.width,
        fields: m.fields.map((f) => [f.name, f.offset, f.datatype, f.count]),
        is_bigendian: m.is_bigendian,
        point_step: m.point_step,
        row_step: m.row_step,
        is_dense: m.is_dense,
        data_sha256: crypto.createHash("sha256").update(m.data).digest("hex"),
      };
    case "sensor_msgs/msg/Imu":
      return {
        stamp: stampOf(m.header),
        frame: m.header.frame_id,
        orientation: [m.orientation.x, m.orientation.y, m.orientation.z, m.orientation.w],
        orientation_covariance: Array.from(m.orientation_covariance),
        accelerometer: [m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z],
        gyroscope: [m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z],
        accelerometer_covariance: Array.from(m.linear_acceleration_covariance),
        gyroscope_covariance: Array.from(m.angular_velocity_covariance),
      };
    case "nav_msgs/msg/Odometry": {
      const p = m.pose.pose.position, q = m.pose.pose.orientation;
      const v = m.twist.twist.linear, w = m.twist.twist.angular;
      return {
        stamp: stampOf(m.header),
        frame: m.header.frame_id,
        child: m.child_frame_id,
        pose: [p.x, p.y, p.z, q.x, q.y, q.z, q.w],
        twist: [v.x, v.y, v.z, w.x, w.y, w.z],
      };
    }
    case "tf2_msgs/msg/TFMessage":
      return m.transforms.map((t) => ({
        stamp: stampOf(t.header),
        parent: t.header.frame_id,
        child: t.child_frame_id,
        translation: [t.transform.translation.x, t.transform.translation.y,
                      t.transform.translation.z],
        rotation: [t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
                   t.transform.rotation.w],
      }));
    case "std_msgs/msg/String":
      return m.data;
    case "sensor_msgs/msg/CompressedImage":
      return {
        stamp: stampOf(m.header),
        frame: m.header.frame_id,
        format: m.format,
        data_base64: Buffer.from(m.data).toString("base64"),
      };
    case "sensor_msgs/msg/CameraInfo":
      return {
        stamp: stampOf(m.header),
        frame: m.header.frame_id,
        height: m.height,
        width: m.width,
        distortion_model: m.distortion_model,
        d: Array.from(m.d),
        k: Array.from(m.k),
        r: Array.from(m.r),
        p: Array.from(m.p),
        binning: [m.binning_x, m.binning_y],
        roi: [m.roi.x_offset, m.roi.y_offset, m.roi.height, m.roi.width, m.roi.do_rectify],
      };
    default:
      throw new Error(`unexpected type ${type}`);
  }
}

async function main() {
  const { reader, handle, decompressHandlers } = await openIndexedMcap(file, modules);
  const out = {
    header: reader.header,
    statistics: {
      message_count: Number(reader.statistics.messageCount),
      schema_count: reader.statistics.schemaCount,
      channel_count: reader.statistics.channelCount,
      chunk_count: reader.statistics.chunkCount,
      message_start_time: reader.statistics.messageStartTime.toString(),
      message_end_time: reader.statistics.messageEndTime.toString(),
    },
    chunk_indexes: reader.chunkIndexes.length,
    compression: [...new Set(reader.chunkIndexes.map((c) => c.compression))],
    schemas: {},
    channels: {},
    messages: {},
  };
  const readers = new Map();
  for (const [id, schema] of reader.schemasById) {
    out.schemas[id] = { name: schema.name, encoding: schema.encoding };
  }
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    out.channels[channel.topic] = {
      id,
      type: schema.name,
      message_encoding: channel.messageEncoding,
      schema_encoding: schema.encoding,
      metadata: Object.fromEntries(channel.metadata),
      count: Number(reader.statistics.channelMessageCounts.get(id)),
    };
    const definition = new TextDecoder().decode(schema.data);
    readers.set(id, [schema.name, new MessageReader(parse(definition, { ros2: true }))]);
    out.messages[channel.topic] = [];
  }
  // Every message through the indexes (the indexed reader checks each chunk's CRC), in log time
  // order; log time and publish time must be the header's stamp.
  let last = -1n;
  out.log_time_errors = 0;
  for await (const message of reader.readMessages()) {
    const channel = reader.channelsById.get(message.channelId);
    const [type, decoder] = readers.get(message.channelId);
    const decoded = decoder.readMessage(message.data);
    const summary = summarise(type, decoded);
    const stamp = Array.isArray(summary) ? summary[0].stamp : summary.stamp;
    if (stamp) {
      const ns = BigInt(stamp[0]) * 1000000000n + BigInt(stamp[1]);
      if (ns !== message.logTime || message.publishTime !== message.logTime) ++out.log_time_errors;
    }
    if (message.logTime < last) ++out.log_time_errors;
    last = message.logTime;
    out.messages[channel.topic].push(summary);
  }
  // The data section's CRC (the indexed reader does not check it), and the stream reader's
  // walk through every record with its CRC checks.
  const bytes = await fs.readFile(file);
  out.data_section_crc_ok =
      reader.dataSectionCrc !== undefined &&
      crc32(bytes.subarray(0, Number(reader.dataEndOffset))) === reader.dataSectionCrc;
  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(bytes);
  let streamed = 0;
  for (let record; (record = stream.nextRecord()); ) {
    if (record.type === "Message") ++streamed;
  }
  out.stream_messages = streamed;
  out.stream_done = stream.done();
  await handle.close();
  process.stdout.write(JSON.stringify(out));
}

main().catch((error) => {
  process.stderr.write(`${error.stack || error}\n`);
  process.exit(1);
});
