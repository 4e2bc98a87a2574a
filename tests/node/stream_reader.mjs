// The one way the node tests open an MCAP stream: @mcap/core's McapStreamReader
// (what Foxglove uses), checking every CRC, with zstd and lz4 chunks decompressed
// by the pure-JS fzstd and lz4js packages.
import { McapStreamReader } from "@mcap/core";
import { decompress as unzstd } from "fzstd";
import lz4 from "lz4js";

export function streamReader() {
  return new McapStreamReader({
    validateCrcs: true,
    decompressHandlers: {
      zstd: (data, size) => unzstd(data, new Uint8Array(Number(size))),
      lz4: (data, size) => {
        const out = new Uint8Array(Number(size));
        lz4.decompressFrame(data, out);
        return out;
      },
    },
  });
}
