// Reads a run's MCAP file (isg run --mcap, isg export RUN_DIR --mcap) with the reference readers
// from npm (ci/oracles, pinned): @mcap/core's indexed reader, @foxglove/rosmsg2-serialization for
// the CDR scans, and checks every JSON message with ajv against two JSON Schemas: the one the file
// carries for its channel, and Foxglove's own from @foxglove/schemas (for the foxglove.* types).
// Prints one JSON document: the header, the channels with their schemas, every message decoded
// (JSON messages whole; a cloud's header and size), and every validation failure.
// usage: node run_mcap_oracle.js FILE.mcap NODE_MODULES_DIR
"use strict";
const path = require("path");

const [file, modules] = process.argv.slice(2);
const need = (name) => require(path.join(modules, name));
const { openIndexedMcap } = require("./mcap_open.js");
const { parse } = need("@foxglove/rosmsg");
const { MessageReader } = need("@foxglove/rosmsg2-serialization");
const Ajv = need("ajv");
const foxgloveSchemas = need("@foxglove/schemas/jsonschema");

async function main() {
  const { reader, handle } = await openIndexedMcap(file, modules);
  // Foxglove's schemas are draft-07 with descriptive keywords ajv's strict mode does not know.
  const ajv = new Ajv({ allErrors: true, strict: false });
  const out = {
    header: reader.header,
    message_count: Number(reader.statistics.messageCount),
    channels: {},
    messages: {},
    invalid: [],
    rejects_broken: {},
    log_time_errors: 0,
  };
  const decoders = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    const text = new TextDecoder().decode(schema.data);
    out.channels[channel.topic] = {
      type: schema.name,
      schema_encoding: schema.encoding,
      message_encoding: channel.messageEncoding,
      count: Number(reader.statistics.channelMessageCounts.get(id) ?? 0),
    };
    out.messages[channel.topic] = [];
    if (schema.encoding === "jsonschema") {
      const own = ajv.compile(JSON.parse(text));
      const short = schema.name.startsWith("foxglove.") ? schema.name.slice(9) : null;
      const official = short && foxgloveSchemas[short] ? ajv.compile(foxgloveSchemas[short]) : null;
      out.channels[channel.topic].foxglove_schema = official !== null;
      decoders.set(id, { json: true, own, official, required: JSON.parse(text).required });
    } else {
      decoders.set(id, { json: false, reader: new MessageReader(parse(text, { ros2: true })) });
    }
  }
  let last = -1n;
  for await (const message of reader.readMessages()) {
    const channel = reader.channelsById.get(message.channelId);
    const decoder = decoders.get(message.channelId);
    if (message.logTime < last || message.publishTime !== message.logTime) ++out.log_time_errors;
    last = message.logTime;
    const entry = { log_time: message.logTime.toString() };
    if (decoder.json) {
      const value = JSON.parse(new TextDecoder().decode(message.data));
      for (const [name, validate] of [["own", decoder.own], ["foxglove", decoder.official]]) {
        if (validate && !validate(value) && out.invalid.length < 20) {
          out.invalid.push({ topic: channel.topic, schema: name, errors: validate.errors });
        } else if (validate && !validate(value)) {
          out.invalid.push({ topic: channel.topic, schema: name });
        }
      }
      entry.value = value;
      // The validators must reject the channel's first message without the first field its schema requires: a
      // schema that accepts anything would pass every message.
      if (!(channel.topic in out.rejects_broken)) {
        const broken = { ...value };
        delete broken[decoder.required[0]];
        out.rejects_broken[channel.topic] = [decoder.own, decoder.official]
            .filter((validate) => validate)
            .every((validate) => !validate(broken));
      }
    } else {
      const m = decoder.reader.readMessage(message.data);
      entry.value = {
        stamp: [m.header.stamp.sec, m.header.stamp.nanosec],
        frame: m.header.frame_id,
        width: m.width,
        point_step: m.point_step,
        bytes: m.data.length,
      };
    }
    out.messages[channel.topic].push(entry);
  }
  await handle.close();
  process.stdout.write(JSON.stringify(out));
}

main().catch((error) => {
  process.stderr.write(`${error.stack || error}\n`);
  process.exit(1);
});
