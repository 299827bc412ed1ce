#!/usr/bin/env python3
"""Each exported file applied with its tool's own correction formula, written
here from the tool's source, to the raw readings of the Xsens recording, and
compared with `mpcal apply` on the same rows.

  imu_tk (include/imu_tk/calibration.h, CalibratedTriad_::unbiasNormalize):
      X' = T*K*(X - B), the .calib read as 21 numbers with >> (load()).
  Kalibr (IccSensors.py, IccScaledMisalignedImu, forward model):
      alpha = M_a*a + b_a,  w_m = M_g*C_gyro_i*w + A*C_gyro_i*a + b_g
  OpenVINS (ov_msckf/src/state/Propagator.cpp):
      a = R_IMUtoACC^T*Ta^-1*(a_m - b_a),  w = R_IMUtoGYRO^T*Tw^-1*(w_m - b_g - Tg*a)

Kalibr's and OpenVINS's files hold no biases (the filter estimates its own):
the test takes them from the calibration file, as a filter would converge to
them. imu_tk's frame keeps z, mpcal's x: its output is mpcal's turned by the
rotation R the file's comment gives, and its gyroscope file cannot hold the
g-sensitivity G: its output differs from mpcal's by R^T*M*G*a, asserted here.

Usage: formula_test.py MPCAL SOURCE_DIR WORK_DIR
"""
import json
import os
import subprocess
import sys

import numpy as np
import yaml

MPCAL, SRC, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
XSENS = os.path.join(SRC, "tests/data/real/xsens-multiposition")
NOISE = os.path.join(SRC, "tests/data/noise_still.json")
os.makedirs(WORK, exist_ok=True)
failures = []


def run(*args):
    r = subprocess.run([MPCAL, *args], cwd=WORK, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mpcal {' '.join(args)} failed: {r.stderr}")
    return r


def check(name, got, want, tol):
    err = np.max(np.abs(got - want))
    print(f"{name}: largest difference {err:.3g} (tolerance {tol:.3g})")
    if not err <= tol:
        failures.append(name)


# mpcal's calibration of the whole IMU, and a raw log of every 5th row.
run("calibrate", os.path.join(XSENS, "xsens_acc.mat"), "--gyro-log",
    os.path.join(XSENS, "xsens_gyro.mat"), "--units", "counts", "--gyro-units", "counts",
    "--gravity", "9.81744", "-o", "imu.json")
calib = json.load(open(os.path.join(WORK, "imu.json")))
acc = np.loadtxt(os.path.join(XSENS, "xsens_acc.mat"))[::5]
gyr = np.loadtxt(os.path.join(XSENS, "xsens_gyro.mat"))[::5]
raw_a, raw_w = acc[:, 1:4], gyr[:, 1:4]
with open(os.path.join(WORK, "raw.csv"), "w") as f:
    f.write("t,ax,ay,az,gx,gy,gz\n")
    for t, a, w in zip(acc[:, 0], raw_a, raw_w):
        f.write(f"{t:.6f},{a[0]:.0f},{a[1]:.0f},{a[2]:.0f},{w[0]:.0f},{w[1]:.0f},{w[2]:.0f}\n")
run("apply", "imu.json", "raw.csv", "-o", "out.csv", "--columns",
    "t=t,ax=ax,ay=ay,az=az,gx=gx,gy=gy,gz=gz")
out = np.loadtxt(os.path.join(WORK, "out.csv"), delimiter=",", skiprows=1)
a_mpcal, w_mpcal = out[:, 1:4], out[:, 4:7]
# apply writes every digit of a double: the tolerances are rounding of the
# few products in between (1e-12 of the largest value).
tol_a = 1e-12 * np.max(np.abs(a_mpcal))
tol_w = 1e-12 * np.max(np.abs(w_mpcal))

g = calib["gyroscope"]
# SI readings, as Kalibr and OpenVINS take them: the raw counts times the
# nominal factors the files' first comment lines give.


def nominal_factors(text):
    for line in text.splitlines():
        if line.startswith("# Readings in m/s^2 and rad/s"):
            words = line.replace("(", " ").split()
            times = [i for i, w in enumerate(words) if w == "times"]
            return float(words[times[0] + 1]), float(words[times[1] + 1])
    sys.exit("no nominal factors in the file's comments")


def biases(text):
    for line in text.splitlines():
        if line.startswith("# Biases"):
            parts = line.split("[")
            b_a = [float(x) for x in parts[1].split("]")[0].split(",")]
            b_w = [float(x) for x in parts[2].split("]")[0].split(",")]
            return np.array(b_a), np.array(b_w)
    sys.exit("no biases in the file's comments")


def read_calib(path):
    # imu_tk's load(): 21 numbers read with >>, the rest of the file ignored.
    v = [float(x) for x in open(path).read().split("#")[0].split()]
    assert len(v) == 21, path
    return np.array(v[:9]).reshape(3, 3), np.array(v[9:18]).reshape(3, 3), np.array(v[18:])


def rotation_in_comment(path):
    for line in open(path):
        if line.startswith("# ["):
            return np.array([float(x) for x in line[3:].split("]")[0].split(",")]).reshape(3, 3)
    sys.exit(f"{path}: no rotation in the comments")


# ----- imu_tk -----
run("export", "imu-tk-accel", "imu.json", "-o", "acc.calib")
run("export", "imu-tk-gyro", "imu.json", "-o", "gyro.calib")
T, K, B = read_calib(os.path.join(WORK, "acc.calib"))
a_tk = (T @ K @ (raw_a - B).T).T
R = rotation_in_comment(os.path.join(WORK, "acc.calib"))
check("imu_tk rotation is a rotation", R.T @ R, np.eye(3), 1e-12)
check("imu_tk accelerometer T upper unit-triangular", np.tril(T, -1), np.zeros((3, 3)), 0)
check("imu_tk accelerometer = R^T * mpcal apply", a_tk, a_mpcal @ R, tol_a)
check("imu_tk accelerometer magnitude = mpcal's", np.linalg.norm(a_tk, axis=1),
      np.linalg.norm(a_mpcal, axis=1), tol_a)
Tg, Kg, Bg = read_calib(os.path.join(WORK, "gyro.calib"))
w_tk = (Tg @ Kg @ (raw_w - Bg).T).T
# Row-major 3x3 in the calibration file (docs/formats.md).
M = np.array(g["m"]).reshape(3, 3)
G = (np.array(g["g_sensitivity_radps_per_mps2"]).reshape(3, 3)
     if "g_sensitivity_radps_per_mps2" in g else np.zeros((3, 3)))
dropped = (M @ G @ a_mpcal.T).T
print(f"imu_tk gyroscope: the g-sensitivity dropped is up to {np.max(np.abs(dropped)):.3g} rad/s")
check("imu_tk gyroscope = R^T * (mpcal apply + M*G*a)", w_tk, (w_mpcal + dropped) @ R, tol_w)

# ----- Kalibr, scale-misalignment -----
run("export", "kalibr-scale-misalignment", "imu.json", NOISE, "-o", "kalibr.yaml")
text = open(os.path.join(WORK, "kalibr.yaml")).read()
k = yaml.safe_load(text)["imu0"]
fa, fw = nominal_factors(text)
b_a, b_w = biases(text)
Ma = np.array(k["accelerometers"]["M"])
Mg, A, C = (np.array(k["gyroscopes"][n]) for n in ("M", "A", "C_gyro_i"))
check("Kalibr M_a lower triangular", np.triu(Ma, 1), np.zeros((3, 3)), 0)
check("Kalibr M_g lower triangular", np.triu(Mg, 1), np.zeros((3, 3)), 0)
check("Kalibr C_gyro_i a rotation", C.T @ C, np.eye(3), 1e-12)
alpha, w_m = raw_a * fa, raw_w * fw
a_k = np.linalg.solve(Ma, (alpha - b_a).T).T
check("Kalibr accelerometer = mpcal apply", a_k, a_mpcal, tol_a)
w_k = (C.T @ np.linalg.solve(Mg, (w_m - b_w - (A @ C @ a_k.T).T).T)).T
check("Kalibr gyroscope = mpcal apply", w_k, w_mpcal, tol_w)
# The noise keys: the largest axis of the noise file (mpcal's Kalibr rule).
noise = json.load(open(NOISE))
for key, sensor, term in (("gyroscope_noise_density", "gyroscope", "white_noise_radps_per_rthz"),
                          ("accelerometer_noise_density", "accelerometer",
                           "white_noise_mps2_per_rthz")):
    largest = max(noise[sensor]["axes"][a][term]["value"] for a in "xyz")
    check(f"Kalibr {key} = the noise file's largest axis", np.array([k[key]]),
          np.array([largest]), 0)

# ----- OpenVINS -----
run("export", "openvins", "imu.json", NOISE, "-o", "kalibr_imu_chain.yaml")
text = open(os.path.join(WORK, "kalibr_imu_chain.yaml")).read()
assert text.startswith("%YAML:1.0\n")
o = yaml.safe_load(text.split("\n", 1)[1])["imu0"]
Tw, Ta, Rg, Ra, Tgs = (np.array(o[n]) for n in ("Tw", "Ta", "R_IMUtoGYRO", "R_IMUtoACC", "Tg"))
assert o["model"] == "kalibr"
fa, fw = nominal_factors(text)
b_a, b_w = biases(text)
a_o = (Ra.T @ np.linalg.inv(Ta) @ (raw_a * fa - b_a).T).T
check("OpenVINS accelerometer = mpcal apply", a_o, a_mpcal, tol_a)
w_o = (Rg.T @ np.linalg.inv(Tw) @ (raw_w * fw - b_w - (Tgs @ a_o.T).T).T).T
check("OpenVINS gyroscope = mpcal apply", w_o, w_mpcal, tol_w)

if failures:
    sys.exit("FAILED: " + "; ".join(failures))
print("all formulas agree")
