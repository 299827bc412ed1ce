#!/usr/bin/python3
"""Splits one simulated session into the two streams phone apps and ROS
drivers write: the accelerometer and the gyroscope each at its own rate and
stamps. Written without mpcal's reader or resampler (only its simulator makes
the dense session), so that what mpcal joins is what these tools write.

  /usr/bin/python3 make_streams.py DENSE.csv OUTDIR   (Debian's python: rosbag)

DENSE.csv is `mpcal simulate static --gyro ... --rate 2000` (t in s, ax ay az
in m/s2, gx gy gz in rad/s). Each stream takes the dense row nearest to each
of its own stamps, k / rate after its own start (the gyroscope starts 3.1 ms
after the accelerometer, and each stamp has a jitter of up to a quarter of
the dense period), with the row's own time; the readings are the row's as
written. Writes into OUTDIR:

- Sensor Logger (Android) export, as its UNITS.md and the files it writes
  state (github.com/tszheichoi/awesome-sensor-logger, UNITS.md "Time",
  "Accelerometer", "Gyroscope"): `TotalAcceleration.csv` (acceleration with
  gravity, m/s2) and `Gyroscope.csv` (rad/s), each with the header
  `time,seconds_elapsed,z,y,x`: `time` in ns since the Unix epoch,
  `seconds_elapsed` in s since the recording's start, the axes in z, y, x
  order; and `Accelerometer.csv`, Android's acceleration without gravity
  (here each reading less the mean of the readings within half a second of
  it, the low-passed gravity a phone's sensor fusion takes out).
- phyphox export (github.com/phyphox/phyphox-experiments, accelerometer.phyphox
  and gyroscope.phyphox, their <export> sets): `Accelerometer.csv` with
  "Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)",
  "Acceleration z (m/s^2)","Absolute acceleration (m/s^2)" and
  `Gyroscope.csv` with "Time (s)","Gyroscope x (rad/s)",...,
  "Absolute (rad/s)", times from the experiment's start, comma-separated,
  quoted names as phyphox's CSV (comma, decimal point) export writes them.
- with --bag: `two_rate.bag` (python3-rosbag): sensor_msgs/Imu on
  /camera/accel/sample (linear acceleration; angular velocity zero, as
  realsense-ros fills it) and /camera/gyro/sample (angular velocity; linear
  acceleration zero), header stamps 1700000000 s + t, bz2 chunks; /imu/data
  with both sensors at the accelerometer's stamps (the dense rows the
  accelerometer stream took), the single-stream reference; and /chatter
  (std_msgs/String) once, a topic of another type.
- with --csv: `accel.csv` (t,ax,ay,az) and `gyro.csv` (t,gx,gy,gz) at their
  own stamps, and the single-stream references of the validation study
  (docs/validation.md): `single_at_accel.csv` and `single_at_gyro.csv`
  (t,ax,ay,az,gx,gy,gz), both sensors from the dense rows of the one
  stream's stamps.

Options: --accel-rate HZ (default 50), --gyro-rate HZ (default 100),
--format sensorlogger|phyphox|bag|csv (may repeat; default all but csv).
"""
import argparse
import csv
import math
import os
import random

EPOCH_NS = 1_700_000_000 * 10**9
GYRO_START_S = 0.0031


def read_dense(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    t = [float(r["t"]) for r in rows]
    a = [(float(r["ax"]), float(r["ay"]), float(r["az"])) for r in rows]
    g = [(float(r["gx"]), float(r["gy"]), float(r["gz"])) for r in rows]
    return t, a, g


def stream_rows(t, rate_hz, start_s, rng):
    """Indices of the dense rows nearest a stream's jittered stamps."""
    dense_period = (t[-1] - t[0]) / (len(t) - 1)
    out = []
    k = 0
    while True:
        stamp = t[0] + start_s + k / rate_hz + rng.uniform(-0.25, 0.25) * dense_period
        if stamp > t[-1]:
            break
        i = min(len(t) - 1, max(0, round((stamp - t[0]) / dense_period)))
        if not out or i > out[-1]:
            out.append(i)
        k += 1
    return out


def gravity_removed(t, a, ia):
    """Each row less its mean over the second around it: the low-passed
    gravity a phone's sensor fusion takes out (zero when still)."""
    sums = [(0.0, 0.0, 0.0)]
    for i in ia:
        sums.append(tuple(sums[-1][k] + a[i][k] for k in range(3)))
    out, lo, hi = {}, 0, 0
    for n, i in enumerate(ia):
        while t[ia[lo]] < t[i] - 0.5:
            lo += 1
        while hi < len(ia) and t[ia[hi]] <= t[i] + 0.5:
            hi += 1
        mean = [(sums[hi][k] - sums[lo][k]) / (hi - lo) for k in range(3)]
        out[i] = tuple(a[i][k] - mean[k] for k in range(3))
    return out


def write_sensor_logger(out, t, a, g, ia, ig):
    linear = gravity_removed(t, a, ia)
    def rows(name, idx, values):
        with open(os.path.join(out, name), "w", newline="") as f:
            f.write("time,seconds_elapsed,z,y,x\n")
            for i in idx:
                x, y, z = values(i)
                ns = EPOCH_NS + round(t[i] * 1e9)
                f.write("%d,%.6f,%r,%r,%r\n" % (ns, t[i] - t[ia[0]], z, y, x))
    rows("TotalAcceleration.csv", ia, lambda i: a[i])
    rows("Accelerometer.csv", ia, lambda i: linear[i])
    rows("Gyroscope.csv", ig, lambda i: g[i])


def write_phyphox(out, t, a, g, ia, ig):
    def rows(name, names, idx, values):
        with open(os.path.join(out, name), "w", newline="") as f:
            f.write(",".join('"%s"' % n for n in names) + "\n")
            for i in idx:
                v = values(i)
                mag = math.sqrt(sum(c * c for c in v))
                f.write("%.9E,%.9E,%.9E,%.9E,%.9E\n" % (t[i] - t[ia[0]], v[0], v[1], v[2], mag))
    rows("Accelerometer.csv",
         ["Time (s)", "Acceleration x (m/s^2)", "Acceleration y (m/s^2)",
          "Acceleration z (m/s^2)", "Absolute acceleration (m/s^2)"], ia, lambda i: a[i])
    rows("Gyroscope.csv",
         ["Time (s)", "Gyroscope x (rad/s)", "Gyroscope y (rad/s)",
          "Gyroscope z (rad/s)", "Absolute (rad/s)"], ig, lambda i: g[i])


def write_csv(out, t, a, g, ia, ig):
    with open(os.path.join(out, "accel.csv"), "w") as f:
        f.write("t,ax,ay,az\n")
        for i in ia:
            f.write("%r,%r,%r,%r\n" % ((t[i],) + a[i]))
    with open(os.path.join(out, "gyro.csv"), "w") as f:
        f.write("t,gx,gy,gz\n")
        for i in ig:
            f.write("%r,%r,%r,%r\n" % ((t[i],) + g[i]))
    for name, rows in (("single_at_accel.csv", ia), ("single_at_gyro.csv", ig)):
        with open(os.path.join(out, name), "w") as f:
            f.write("t,ax,ay,az,gx,gy,gz\n")
            for i in rows:
                f.write("%r,%r,%r,%r,%r,%r,%r\n" % ((t[i],) + a[i] + g[i]))


def write_bags(out, t, a, g, ia, ig):
    import rosbag
    import rospy
    from sensor_msgs.msg import Imu
    from std_msgs.msg import String

    def imu(i, acc, gyr, seq):
        m = Imu()
        m.header.seq = seq
        m.header.stamp = rospy.Time(nsecs=EPOCH_NS + round(t[i] * 1e9))
        m.header.frame_id = "imu_link"
        m.orientation_covariance[0] = -1.0
        m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = acc
        m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z = gyr
        return m, m.header.stamp

    zero = (0.0, 0.0, 0.0)
    events = [(t[i], "/camera/accel/sample", i, True) for i in ia]
    events += [(t[i], "/camera/gyro/sample", i, False) for i in ig]
    events.sort()
    with rosbag.Bag(os.path.join(out, "two_rate.bag"), "w", compression="bz2") as bag:
        bag.write("/chatter", String(data="two streams"),
                  rospy.Time(nsecs=EPOCH_NS + round(t[0] * 1e9)))
        for seq, (_, topic, i, is_accel) in enumerate(events):
            m, stamp = imu(i, a[i] if is_accel else zero, zero if is_accel else g[i], seq)
            bag.write(topic, m, stamp)
        # The single-stream reference, in the same file: both sensors on
        # the accelerometer's stamps, as one logger sampling both at the
        # accelerometer's rate would write them.
        for seq, i in enumerate(ia):
            m, stamp = imu(i, a[i], g[i], seq)
            bag.write("/imu/data", m, stamp)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dense")
    p.add_argument("out")
    p.add_argument("--accel-rate", type=float, default=50.0)
    p.add_argument("--gyro-rate", type=float, default=100.0)
    p.add_argument("--format", action="append",
                   choices=["sensorlogger", "phyphox", "bag", "csv"])
    p.add_argument("--seed", type=int, default=7)
    args = p.parse_args()
    formats = args.format or ["sensorlogger", "phyphox", "bag"]
    rng = random.Random(args.seed)
    t, a, g = read_dense(args.dense)
    ia = stream_rows(t, args.accel_rate, 0.0, rng)
    ig = stream_rows(t, args.gyro_rate, GYRO_START_S, rng)
    os.makedirs(args.out, exist_ok=True)
    if "sensorlogger" in formats:
        d = os.path.join(args.out, "sensor_logger")
        os.makedirs(d, exist_ok=True)
        write_sensor_logger(d, t, a, g, ia, ig)
    if "phyphox" in formats:
        d = os.path.join(args.out, "phyphox")
        os.makedirs(d, exist_ok=True)
        write_phyphox(d, t, a, g, ia, ig)
    if "bag" in formats:
        write_bags(args.out, t, a, g, ia, ig)
    if "csv" in formats:
        write_csv(args.out, t, a, g, ia, ig)


if __name__ == "__main__":
    main()
