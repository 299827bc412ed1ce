// Checks an MCAP file written by `mpcal apply` with Foxglove's own readers
// (@mcap/core, @foxglove/cdr, not mpcal):
//
//   node apply_bag_mcap.mjs PACKAGES_DIR INPUT.mcap OUTPUT.mcap CORRECTED.csv [TOPIC [NOISE.json]]
//
// PACKAGES_DIR holds node_modules with @mcap/core 2.2.2, @mcap/support 1.1.0
// (@foxglove/wasm-zstd), @foxglove/cdr 3.5.0 and lz4js 0.2.0, as
// tests/data/bags/make_mcap.mjs says. McapStreamReader reads both files
// record by record, checking each chunk's CRC-32; McapIndexedReader reads
// OUTPUT.mcap through its footer, summary (its CRC-32 checked), chunk indexes
// and message indexes, and must give the same messages. Then: the same
// schemas and channels; every message of another topic byte for byte, with
// its times and sequence; every IMU message with its times, header stamp,
// frame_id, orientation and covariances as they were and its linear
// acceleration and angular velocity equal to the row of CORRECTED.csv to
// 1e-12 relative. With NOISE.json (`apply --noise`) the linear acceleration
// and angular velocity covariances are instead N² f on the diagonal and 0
// elsewhere (N the file's white noise per axis, f = (n − 1) / (last − first
// log time) of the topic's n messages), to 1e-12 relative.
import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";

const [packages, input, output, corrected, topic = "/imu/data", noise] = process.argv.slice(2);
const require = createRequire(path.join(packages, "package.json"));
const { McapStreamReader, McapIndexedReader } = require("@mcap/core");
const { CdrReader } = require("@foxglove/cdr");
const zstd = require("@foxglove/wasm-zstd");
const lz4js = require("lz4js");
await zstd.isLoaded;

const decompressHandlers = {
  lz4: (buffer, size) => lz4js.decompress(buffer, Number(size)),
  zstd: (buffer, size) => zstd.decompress(buffer, Number(size)),
};

function fail(what) {
  console.log(`apply_bag_mcap.mjs: ${what}`);
  process.exit(1);
}

function readAll(file) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(fs.readFileSync(file));
  const schemas = new Map();
  const channels = new Map();
  const messages = [];
  let footer = false;
  for (let rec; (rec = reader.nextRecord()); ) {
    if (rec.type === "Schema") schemas.set(rec.id, rec);
    if (rec.type === "Channel") channels.set(rec.id, rec);
    if (rec.type === "Message") messages.push(rec);
    if (rec.type === "Footer") footer = true;
  }
  if (!reader.done()) fail(`${file}: the stream reader did not reach the end`);
  return { schemas, channels, messages, footer };
}

function decodeImu(data, encoding) {
  const m = { doubles: [] };
  if (encoding === "cdr") {
    const r = new CdrReader(data);
    m.stamp = [r.int32(), r.uint32()];
    m.frame = r.string();
    for (let i = 0; i < 37; i++) m.doubles.push(r.float64());
    if (r.offset !== data.byteLength) fail("bytes after an IMU message");
  } else {
    const v = new DataView(data.buffer, data.byteOffset, data.byteLength);
    m.stamp = [v.getUint32(0, true), v.getUint32(4, true), v.getUint32(8, true)];
    const n = v.getUint32(12, true);
    m.frame = Buffer.from(data.subarray(16, 16 + n)).toString();
    for (let i = 0; i < 37; i++) m.doubles.push(v.getFloat64(16 + n + 8 * i, true));
  }
  // orientation 0-3 and its covariance 4-12, angular velocity 13-15 and its
  // covariance 16-24, linear acceleration 25-27 and its covariance 28-36.
  m.kept = [...m.doubles.slice(0, 13), ...m.doubles.slice(16, 25), ...m.doubles.slice(28)];
  m.vectors = [...m.doubles.slice(25, 28), ...m.doubles.slice(13, 16)];
  return m;
}

const close = (a, b) => Math.abs(a - b) <= 1e-12 * Math.max(1, Math.abs(a), Math.abs(b));
const same = (a, b) => Buffer.compare(Buffer.from(a), Buffer.from(b)) === 0;
const json = (x) => JSON.stringify(x, (k, v) => (typeof v === "bigint" ? v.toString() : v instanceof Uint8Array ? Buffer.from(v).toString("hex") : v instanceof Map ? [...v] : v));

const rows = fs.readFileSync(corrected, "utf8").trim().split("\n");
const names = rows.shift().split(",");
const want = rows.map((l) => {
  const v = l.split(",").map(Number);
  return ["ax", "ay", "az", "gx", "gy", "gz"].map((n) => v[names.indexOf(n)]);
});

const a = readAll(input);
// The covariances `apply --noise` sets: linear acceleration's 9, then angular velocity's.
let expectedCov;
if (noise) {
  const ids = [...a.channels.values()].filter((c) => c.topic === topic).map((c) => c.id);
  const times = a.messages.filter((m) => ids.includes(m.channelId)).map((m) => Number(m.logTime));
  const rate = (times.length - 1) / ((times[times.length - 1] - times[0]) * 1e-9);
  const d = JSON.parse(fs.readFileSync(noise, "utf8"));
  const diag = (sensor, key) => {
    const n = ["x", "y", "z"].map((k) => d[sensor].axes[k][key].value);
    return [0, 1, 2].flatMap((i) => [0, 1, 2].map((j) => (i === j ? n[i] ** 2 * rate : 0)));
  };
  expectedCov = [...diag("accelerometer", "white_noise_mps2_per_rthz"), ...diag("gyroscope", "white_noise_radps_per_rthz")];
}
const b = readAll(output);
if (!b.footer) fail("the output has no footer");
if (json([...a.schemas.values()]) !== json([...b.schemas.values()])) fail("schemas differ");
if (json([...a.channels.values()]) !== json([...b.channels.values()])) fail("channels differ");
if (a.messages.length !== b.messages.length) fail(`${b.messages.length} messages, not ${a.messages.length}`);
let imu = 0;
let other = 0;
for (let i = 0; i < a.messages.length; i++) {
  const [m, n] = [a.messages[i], b.messages[i]];
  if (m.channelId !== n.channelId || m.logTime !== n.logTime || m.publishTime !== n.publishTime || m.sequence !== n.sequence) {
    fail(`message ${i}: channel, times or sequence changed`);
  }
  const channel = a.channels.get(m.channelId);
  if (channel.topic !== topic) {
    if (!same(m.data, n.data)) fail(`message ${i} on ${channel.topic} changed`);
    other++;
    continue;
  }
  const [x, y] = [decodeImu(m.data, channel.messageEncoding), decodeImu(n.data, channel.messageEncoding)];
  if (expectedCov) {
    const got = [...y.doubles.slice(28), ...y.doubles.slice(16, 25)];
    if (json([x.stamp, x.frame, x.doubles.slice(0, 13)]) !== json([y.stamp, y.frame, y.doubles.slice(0, 13)]) ||
        !got.every((v, k) => close(v, expectedCov[k]))) {
      fail(`IMU message ${imu}: header or orientation changed, or covariances ${got}, not ${expectedCov}`);
    }
  } else if (json([x.stamp, x.frame, x.kept]) !== json([y.stamp, y.frame, y.kept])) {
    fail(`IMU message ${imu}: header, orientation or a covariance changed`);
  }
  if (!y.vectors.every((v, k) => close(v, want[imu][k]))) {
    fail(`IMU message ${imu}: ${y.vectors}, the CSV row says ${want[imu]}`);
  }
  imu++;
}
if (imu !== want.length) fail(`${imu} IMU messages for ${want.length} rows`);

// Through the index: the same messages, in log-time order.
const bytes = fs.readFileSync(output);
const indexed = await McapIndexedReader.Initialize({
  readable: {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  },
  decompressHandlers,
});
if (indexed.statistics.messageCount !== BigInt(b.messages.length)) fail("the statistics' message count differs");
const key = (m) => `${m.channelId} ${m.logTime} ${m.sequence} ${Buffer.from(m.data).toString("hex")}`;
const chunked = indexed.chunkIndexes.length > 0;
const viaIndex = [];
for await (const m of indexed.readMessages()) viaIndex.push(key(m));
const streamed = b.messages.map(key);
if (chunked && json(viaIndex.sort()) !== json(streamed.sort())) fail("the index gives other messages");
console.log(`${output}: ${imu} IMU messages as the CSV, ${other} others byte for byte, ${chunked ? viaIndex.length + " read through the index" : "no chunks"}`);
