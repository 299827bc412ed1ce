#!/usr/bin/env python3
"""Writes the four logger-shaped sessions in this folder (see README.md).

Plain Python, independent of mpcal's simulator (src/simulate): each file is
shaped as its logger writes it, with a sensor of known errors held still in
a sequence of orientations and turned by hand between them. Deterministic
(fixed seeds); run it from this folder to regenerate the files.
"""
import math
import random

G = 9.80665


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cube_directions():
    """26 directions: faces, edges, corners of a cube."""
    out = []
    for x in (-1, 0, 1):
        for y in (-1, 0, 1):
            for z in (-1, 0, 1):
                if (x, y, z) != (0, 0, 0):
                    out.append(unit([x, y, z]))
    order = sorted(out, key=lambda d: (-sum(abs(c) < 1e-9 for c in d), d))
    return order


def faces_and_edges():
    """The 18 directions of the cube's faces and edges (the corners add
    little for the 9 parameters, and keep the files small)."""
    return cube_directions()[:18]


def faces_and_corners():
    """The 14 directions of the cube's faces and corners."""
    dirs = cube_directions()
    return dirs[:6] + dirs[18:]


def hemisphere_directions():
    """12 directions with z >= 0: up, four 45-degree tilts, four on the
    horizon, three more tilts (a one-hemisphere session on a table)."""
    dirs = [[0, 0, 1]]
    for k in range(4):
        a = k * math.pi / 2
        dirs.append(unit([math.cos(a), math.sin(a), 1.0]))
    for k in range(4):
        a = k * math.pi / 2 + math.pi / 4
        dirs.append([math.cos(a), math.sin(a), 0.0])
    for k in range(3):
        a = k * 2 * math.pi / 3 + 0.3
        dirs.append(unit([math.cos(a), math.sin(a), 0.35]))
    return dirs


class Sensor:
    """a_meas = (1 + s) * (T a_true) + b + noise, T lower triangular with
    small non-orthogonality angles (the paper's 9-parameter model)."""

    def __init__(self, rng, bias_mps2, scale, angles, noise_mps2):
        self.rng = rng
        self.b = bias_mps2
        self.s = scale
        self.yz, self.zx, self.zy = angles
        self.noise = noise_mps2

    def read(self, a):
        ax, ay, az = a
        t = [ax, self.yz * ax + ay, -self.zy * ax + self.zx * ay + az]
        return [(1 + self.s[i]) * t[i] + self.b[i] + self.rng.gauss(0, self.noise)
                for i in range(3)]


def session(rng, directions, rate_hz, hold_s, turn_s, sensor):
    """(t_s, reading in m/s²) samples: rest, each direction held, turns."""
    samples = []
    t = 0.0
    dt = 1.0 / rate_hz
    previous = directions[0]
    for i, d in enumerate(directions):
        if i > 0:
            n = int(turn_s * rate_hz)
            for k in range(n):
                f = (k + 1) / n
                # Off the straight line, so that opposite faces have a path.
                bow = 0.8 * math.sin(math.pi * f)
                v = unit([(1 - f) * p + f * q + bow * w
                          for p, q, w in zip(previous, d, (0.37, 0.61, 0.70))])
                shake = [rng.gauss(0, 1.5) for _ in range(3)]
                a = [G * c + s for c, s in zip(v, shake)]
                samples.append((t, sensor.read(a)))
                t += dt
        for _ in range(int(hold_s * rate_hz)):
            samples.append((t, sensor.read([G * c for c in d])))
            t += dt
        previous = d
    return samples


def arduino_mpu6050():
    """Arduino + MPU-6050 over serial at 115200 baud, ±2 g (16384 LSB/g),
    millis() time stamps at about 100 Hz, raw counts; the capture starts
    with the noise of the serial line and the sketch's boot messages."""
    rng = random.Random(6050)
    sensor = Sensor(rng, [0.35, -0.21, 0.52], [0.012, -0.008, 0.02],
                    (0.004, -0.003, 0.006), 0.035)
    data = session(rng, faces_and_edges(), 100.0, 5.0, 1.5, sensor)
    with open("arduino_mpu6050_serial.txt", "wb") as f:
        f.write(b"\xf8\x00\xfe\x1c\x06\xe0\x00,-0.0\r\n")  # noise, a partial line
        f.write(b"Initializing I2C devices...\r\n")
        f.write(b"Testing device connections...\r\n")
        f.write(b"MPU6050 connection successful\r\n")
        f.write(b"millis,ax,ay,az\r\n")
        t0 = 1873  # ms since power-up when logging starts
        for t, a in data:
            ms = t0 + int(round(t * 1000.0 + rng.uniform(-0.4, 0.4)))
            counts = [max(-32768, min(32767, int(round(c / G * 16384)))) for c in a]
            f.write(f"{ms},{counts[0]},{counts[1]},{counts[2]}\r\n".encode())


def phone_export(name, separator, decimal_comma):
    """A phone app's export of 'Acceleration with g' (phyphox's layout):
    quoted header with units, times in seconds, m/s², 9 significant digits
    in E notation; decimal comma and ';' in locales that use one."""
    rng = random.Random(42)
    sensor = Sensor(rng, [-0.08, 0.11, 0.19], [0.004, 0.006, -0.005],
                    (0.002, 0.001, -0.002), 0.02)
    data = session(rng, faces_and_corners(), 50.0, 5.0, 1.2, sensor)
    cols = ["Time (s)", "Acceleration x (m/s^2)", "Acceleration y (m/s^2)",
            "Acceleration z (m/s^2)", "Absolute acceleration (m/s^2)"]
    with open(name, "w", newline="") as f:
        f.write(separator.join(f'"{c}"' for c in cols) + "\n")
        for t, a in data:
            v = [t + 0.004211] + a + [math.sqrt(sum(c * c for c in a))]
            cells = [f"{x:.9E}" for x in v]
            if decimal_comma:
                cells = [c.replace(".", ",") for c in cells]
            f.write(separator.join(cells) + "\n")


def adxl345_index():
    """An ADXL345 sketch printing a sample counter and g (4 mg/LSB, full
    resolution) separated by spaces, no header; 100 Hz output data rate."""
    rng = random.Random(345)
    sensor = Sensor(rng, [0.29, -0.39, -0.47], [0.018, 0.011, -0.025],
                    (0.005, 0.002, -0.004), 0.04)
    data = session(rng, faces_and_edges(), 100.0, 5.0, 1.5, sensor)
    with open("adxl345_sample_index.txt", "w") as f:
        for n, (_, a) in enumerate(data):
            g = [round(c / G / 0.0039) * 0.0039 for c in a]
            f.write(f"{n} {g[0]:.4f} {g[1]:.4f} {g[2]:.4f}\n")


def one_hemisphere():
    """12 positions on a table, z never pointing down, in g, CSV with time
    in seconds at 50 Hz (a hand-held session that skipped the lower half)."""
    rng = random.Random(12)
    sensor = Sensor(rng, [0.12, -0.09, 0.15], [0.006, -0.004, 0.008],
                    (0.003, -0.002, 0.004), 0.02)
    data = session(rng, hemisphere_directions(), 50.0, 5.0, 2.0, sensor)
    with open("one_hemisphere_12.csv", "w") as f:
        f.write("time,ax,ay,az\n")
        for t, a in data:
            f.write(f"{t:.2f},{a[0] / G:.5f},{a[1] / G:.5f},{a[2] / G:.5f}\n")


if __name__ == "__main__":
    arduino_mpu6050()
    phone_export("phone_export_en.csv", ",", False)
    phone_export("phone_export_de.csv", ";", True)
    adxl345_index()
    one_hemisphere()
