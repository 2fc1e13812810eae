// What the MCAP oracle scripts (mcap_oracle.js, run_mcap_oracle.js) share: npm's indexed MCAP
// reader over a file, with the zstd and LZ4 chunk decompressors, from NODE_MODULES_DIR.
"use strict";
const path = require("path");
const fs = require("fs/promises");

async function openIndexedMcap(file, modules) {
  const need = (name) => require(path.join(modules, name));
  const { McapIndexedReader } = need("@mcap/core");
  const { FileHandleReadable } = need("@mcap/nodejs");
  const zstd = need("@foxglove/wasm-zstd");
  const lz4 = need("@foxglove/wasm-lz4");
  await zstd.isLoaded;
  await lz4.isLoaded;
  const decompressHandlers = {
    zstd: (buffer, size) => zstd.decompress(buffer, Number(size)),
    lz4: (buffer, size) => lz4(buffer, Number(size)),
  };
  const handle = await fs.open(file, "r");
  const reader = await McapIndexedReader.Initialize({
    readable: new FileHandleReadable(handle),
    decompressHandlers,
  });
  return { reader, handle, decompressHandlers };
}

module.exports = { openIndexedMcap };
