// Writes the bag benchmark's MCAP file with Foxglove's own writer
// (@mcap/core), CDR encoder (@foxglove/cdr) and lz4 (lz4js), not mpcal. Run
// it from a directory where the packages are installed (bench/bag_bench.sh
// does so):
//
//   npm install @mcap/core@2.2.2 @foxglove/cdr@3.5.0 lz4js@0.2.0
//   node bag_bench_mcap.mjs CSV OUT.mcap [--compression lz4|zstd|none] [--no-camera]
//
// Each CSV row (t in s, ax ay az in m/s2, gx gy gz in rad/s) becomes one
// sensor_msgs/msg/Imu on /imu/data (CDR little endian), header stamp and
// log time 1700000000 s + t; a sensor_msgs/msg/Image on /camera/image_raw
// every 1/30 s (640x480 mono8, pseudo-random pixels) among them in time
// order (none with --no-camera), in chunks of the writer's default size
// (lz4 by default; zstd level 3 by @foxglove/wasm-zstd; none: stored), with
// its summary and indexes.
import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";

const require = createRequire(path.join(process.cwd(), "package.json"));
const { McapWriter } = require("@mcap/core");
const { CdrWriter } = require("@foxglove/cdr");
const lz4js = require("lz4js");

const EPOCH_NS = 1700000000n * 1000000000n;
const CAMERA_HZ = 30n;
const WIDTH = 640, HEIGHT = 480;
const args = process.argv.slice(2);
const [csvPath, outPath] = args;
const flag = (name) => args.indexOf(name);
const compression = flag("--compression") >= 0 ? args[flag("--compression") + 1] : "lz4";
const camera = flag("--no-camera") < 0;
if (!["lz4", "zstd", "none"].includes(compression)) {
  throw new Error(`unknown compression ${compression} (lz4, zstd or none)`);
}
const zstd = require("@foxglove/wasm-zstd");
await zstd.isLoaded;
const compressChunk = {
  lz4: (data) => ({ compression: "lz4", compressedData: lz4js.compress(data) }),
  zstd: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
  none: undefined,
}[compression];

function stamp(w, ns) {
  w.int32(Number(ns / 1000000000n));
  w.uint32(Number(ns % 1000000000n));
}

// Header, orientation (4) and its covariance (9), angular velocity (3),
// covariance (9), linear acceleration (3), covariance (9).
function cdrImu(v, ns) {
  const w = new CdrWriter();
  stamp(w, ns);
  w.string("imu_link");
  const d = new Array(37).fill(0);
  d[4] = -1; // no orientation (REP 145)
  [d[13], d[14], d[15]] = [v[4], v[5], v[6]];
  [d[25], d[26], d[27]] = [v[1], v[2], v[3]];
  for (const x of d) w.float64(x);
  return w.data;
}

// Eight frames of pseudo-random pixels (a fixed LCG), reused in turn.
let seed = 7;
const frames = Array.from({ length: 8 }, () => {
  const f = new Uint8Array(WIDTH * HEIGHT);
  for (let i = 0; i < f.length; ++i) {
    seed = (Math.imul(seed, 1103515245) + 12345) >>> 0;
    f[i] = seed >>> 24;
  }
  return f;
});

function cdrImage(k, ns) {
  const w = new CdrWriter({ size: WIDTH * HEIGHT + 128 });
  stamp(w, ns);
  w.string("camera");
  w.uint32(HEIGHT);
  w.uint32(WIDTH);
  w.string("mono8");
  w.uint8(0);
  w.uint32(WIDTH);
  w.uint8Array(frames[k % frames.length]);
  return w.data;
}

const fd = fs.openSync(outPath, "w");
let size = 0n;
const writable = {
  position: () => size,
  write: async (buf) => {
    fs.writeSync(fd, buf);
    size += BigInt(buf.length);
  },
};
const writer = new McapWriter({ writable, compressChunk });
await writer.start({ profile: "ros2", library: "bag_bench_mcap.mjs" });
const schema = async (name) =>
  writer.registerSchema({ name, encoding: "ros2msg", data: new TextEncoder().encode("") });
const imuSchema = await schema("sensor_msgs/msg/Imu");
const imageSchema = await schema("sensor_msgs/msg/Image");
const channel = async (topic, schemaId) =>
  writer.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: new Map() });
const imu = await channel("/imu/data", imuSchema);
const cameraChannel = camera ? await channel("/camera/image_raw", imageSchema) : 0;

const lines = fs.readFileSync(csvPath, "utf8").trim().split("\n").slice(1);
let nextFrame = 0n;
for (let i = 0; i < lines.length; ++i) {
  const v = lines[i].split(",").map(Number);
  const ns = EPOCH_NS + BigInt(Math.round(v[0] * 1e9));
  while (camera) {
    const frameNs = EPOCH_NS + (nextFrame * 1000000000n) / CAMERA_HZ;
    if (frameNs > ns) break;
    await writer.addMessage({
      channelId: cameraChannel, sequence: Number(nextFrame), logTime: frameNs, publishTime: frameNs,
      data: cdrImage(Number(nextFrame), frameNs),
    });
    ++nextFrame;
  }
  await writer.addMessage({
    channelId: imu, sequence: i, logTime: ns, publishTime: ns, data: cdrImu(v, ns),
  });
}
await writer.end();
fs.closeSync(fd);
