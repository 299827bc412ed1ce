// Writes the MCAP test files from session.csv with Foxglove's own writer
// (@mcap/core), compressors and CDR encoder (not mpcal). Run it from the
// directory where scripts/install-deps.sh installs them (tests/tools, npm ci
// at the versions its package-lock.json pins):
//
//   cd tests/tools && node ../data/bags/make_mcap.mjs ../data/bags
//
// Each CSV row (t in s, ax ay az in m/s2, gx gy gz in rad/s) becomes one
// sensor_msgs Imu message on /imu/data, as make_ros1_bags.py writes them:
// header stamp kEpoch + t (rows 100 and 101 swapped), log_time 2 ms later,
// frame "imu_link", the row's doubles as they are. A std_msgs String on
// /chatter precedes every tenth row. Files:
//   imu_cdr_zstd.mcap   CDR little endian, zstd chunks, summary and indexes
//   imu_cdr_be_lz4.mcap CDR big endian, lz4 (frame) chunks, summary and indexes
//   imu_ros1.mcap       ROS 1 serialisation, chunks stored uncompressed
//   imu_cdr_plain.mcap  CDR, no chunks, no summary: a reader must scan it
//   imu_chatter_first.mcap  CDR little endian, zstd chunks, summary and
//                       indexes, and 300 /chatter messages before the first
//                       row (1 ms before it), so the first chunks hold no
//                       IMU message (as make_ros1_bags.py's bags)
import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";

const require = createRequire(path.join(process.cwd(), "package.json"));
const { McapWriter } = require("@mcap/core");
const { CdrWriter, EncapsulationKind } = require("@foxglove/cdr");
const zstd = require("@foxglove/wasm-zstd");
const lz4js = require("lz4js");

const EPOCH_NS = 1700000000n * 1000000000n;
const LATENCY_NS = 2000000n;
const SWAPPED = [100, 101];
const out = process.argv[2] ?? ".";

function readRows() {
  const lines = fs.readFileSync(path.join(out, "session.csv"), "utf8").trim().split("\n");
  const names = lines[0].split(",");
  return lines.slice(1).map((l) => {
    const v = l.split(",");
    return Object.fromEntries(names.map((n, i) => [n, v[i]]));
  });
}

// Seconds as a decimal string to ns, exactly as Python's round(float(t)*1e9).
function toNs(t) {
  return BigInt(Math.round(Number(t) * 1e9));
}

// Header, orientation (4) and its covariance (9), angular velocity (3),
// covariance (9), linear acceleration (3), covariance (9).
function imuDoubles(row) {
  const d = new Array(37).fill(0);
  d[4] = -1; // orientation covariance[0]: no orientation (REP 145)
  d[13] = Number(row.gx), d[14] = Number(row.gy), d[15] = Number(row.gz);
  d[25] = Number(row.ax), d[26] = Number(row.ay), d[27] = Number(row.az);
  return d;
}

function cdrImu(row, stampNs, kind) {
  const w = new CdrWriter({ kind });
  w.int32(Number(stampNs / 1000000000n));
  w.uint32(Number(stampNs % 1000000000n));
  w.string("imu_link");
  for (const x of imuDoubles(row)) w.float64(x);
  return w.data;
}

function cdrString(text) {
  const w = new CdrWriter({ kind: EncapsulationKind.CDR_LE });
  w.string(text);
  return w.data;
}

// ROS 1: little endian, no padding; strings as u32 length + bytes.
function ros1Imu(row, seq, stampNs) {
  const frame = Buffer.from("imu_link");
  const b = Buffer.alloc(4 + 8 + 4 + frame.length + 37 * 8);
  let o = b.writeUInt32LE(seq, 0);
  o = b.writeUInt32LE(Number(stampNs / 1000000000n), o);
  o = b.writeUInt32LE(Number(stampNs % 1000000000n), o);
  o = b.writeUInt32LE(frame.length, o);
  o += frame.copy(b, o);
  for (const x of imuDoubles(row)) o = b.writeDoubleLE(x, o);
  return b;
}

function ros1String(text) {
  const s = Buffer.from(text);
  const b = Buffer.alloc(4 + s.length);
  b.writeUInt32LE(s.length, 0);
  s.copy(b, 4);
  return b;
}

async function write(name, { encoding, kind, compress, chunked, warmup = 0 }) {
  const parts = [];
  let size = 0n;
  const writable = {
    position: () => size,
    write: async (buf) => {
      parts.push(Buffer.from(buf));
      size += BigInt(buf.length);
    },
  };
  const writer = new McapWriter({
    writable,
    chunkSize: 8192,
    compressChunk: compress,
    useChunks: chunked,
    useChunkIndex: chunked,
    useMessageIndex: chunked,
    useStatistics: chunked,
    useSummaryOffsets: chunked,
    repeatChannels: chunked,
    repeatSchemas: chunked,
  });
  const ros2 = encoding === "cdr";
  await writer.start({ profile: ros2 ? "ros2" : "ros1", library: "make_mcap.mjs" });
  const imuSchema = await writer.registerSchema({
    name: ros2 ? "sensor_msgs/msg/Imu" : "sensor_msgs/Imu",
    encoding: ros2 ? "ros2msg" : "ros1msg",
    data: new TextEncoder().encode("# sensor_msgs Imu\n"),
  });
  const stringSchema = await writer.registerSchema({
    name: ros2 ? "std_msgs/msg/String" : "std_msgs/String",
    encoding: ros2 ? "ros2msg" : "ros1msg",
    data: new TextEncoder().encode("string data\n"),
  });
  const imu = await writer.registerChannel({
    topic: "/imu/data", schemaId: imuSchema, messageEncoding: encoding, metadata: new Map(),
  });
  const chatter = await writer.registerChannel({
    topic: "/chatter", schemaId: stringSchema, messageEncoding: encoding, metadata: new Map(),
  });
  const rows = readRows();
  const stamps = rows.map((r) => EPOCH_NS + toNs(r.t));
  [stamps[SWAPPED[0]], stamps[SWAPPED[1]]] = [stamps[SWAPPED[1]], stamps[SWAPPED[0]]];
  for (let k = 0; k < warmup; ++k) {
    const logTime = EPOCH_NS + toNs(rows[0].t) + LATENCY_NS - 1000000n + BigInt(k);
    const text = `warming up ${k}`;
    await writer.addMessage({
      channelId: chatter, sequence: k, logTime, publishTime: logTime,
      data: ros2 ? cdrString(text) : ros1String(text),
    });
  }
  for (let i = 0; i < rows.length; ++i) {
    const logTime = EPOCH_NS + toNs(rows[i].t) + LATENCY_NS;
    if (i % 10 === 0) {
      const text = `row ${i}`;
      await writer.addMessage({
        channelId: chatter, sequence: i, logTime, publishTime: logTime,
        data: ros2 ? cdrString(text) : ros1String(text),
      });
    }
    const data = ros2 ? cdrImu(rows[i], stamps[i], kind) : ros1Imu(rows[i], i, stamps[i]);
    await writer.addMessage({ channelId: imu, sequence: i, logTime, publishTime: logTime, data });
  }
  await writer.end();
  fs.writeFileSync(path.join(out, name), Buffer.concat(parts));
}

await zstd.isLoaded;
const zstdChunk = (d) => ({ compression: "zstd", compressedData: zstd.compress(d, 3) });
const lz4Chunk = (d) => {
  const dst = new Uint8Array(lz4js.compressBound(d.length) + 64);
  const n = lz4js.compressFrame(d, dst);
  return { compression: "lz4", compressedData: dst.slice(0, n) };
};
const LE = EncapsulationKind.CDR_LE, BE = EncapsulationKind.CDR_BE;
await write("imu_cdr_zstd.mcap", { encoding: "cdr", kind: LE, compress: zstdChunk, chunked: true });
await write("imu_cdr_be_lz4.mcap", { encoding: "cdr", kind: BE, compress: lz4Chunk, chunked: true });
await write("imu_ros1.mcap", { encoding: "ros1", kind: LE, compress: undefined, chunked: true });
await write("imu_cdr_plain.mcap", { encoding: "cdr", kind: LE, compress: undefined, chunked: false });
await write("imu_chatter_first.mcap", {
  encoding: "cdr", kind: LE, compress: zstdChunk, chunked: true, warmup: 300,
});
