#!/usr/bin/env python3
"""Calibrate imu_tk's Xsens recording from Python and draw the residuals.

    PYTHONPATH=build/python python3 examples/python/calibrate_xsens.py [OUT.png]

Reads the raw counts, calibrates (local gravity 9.81744 m/s²), prints the
parameters with their 1σ and draws, per static position, |a| − g before
(nominal scale only) and after the calibration. Without a display set
MPLBACKEND=Agg.
"""
import pathlib
import sys

import matplotlib.pyplot as plt
import numpy as np

import mpcal

HERE = pathlib.Path(__file__).resolve().parent
LOG = HERE.parents[1] / "tests/data/real/xsens-multiposition/xsens_acc.mat"
GRAVITY_MPS2 = 9.81744  # where it was recorded (the data's README)


def main(out_png):
    rec = mpcal.read_log(LOG, units="counts")
    cal = mpcal.calibrate(rec.t, rec.accel, units="counts", gravity=GRAVITY_MPS2)

    print(f"{len(rec)} rows, {cal.fit.positions} positions")
    for axis, b, s in zip("xyz", cal.bias_mps2, cal.std.bias_mps2):
        print(f"bias {axis}            {b:+.5f} ± {s:.5f} m/s²")
    for axis, k, s in zip("xyz", cal.scale_factor_error, cal.std.scale_factor_error):
        print(f"scale-factor error {axis} {k * 1e6:+9.0f} ± {s * 1e6:.0f} ppm")
    for name in ("yz", "zx", "zy"):
        v, s = cal.non_orthogonality_rad[name], cal.std.non_orthogonality_rad[name]
        print(f"non-orthogonality {name} {v * 1e3:+.3f} ± {s * 1e3:.3f} mrad")

    # Every row corrected, then |a| − g at each position from the rows.
    a_mps2, _ = cal.correct(rec.accel)
    after = []
    for p in cal.positions:
        rows = (rec.t >= p.start_s) & (rec.t <= p.end_s)
        after.append(np.linalg.norm(a_mps2[rows].mean(axis=0)) - GRAVITY_MPS2)
    before = [p.residual_before_mps2 for p in cal.positions]
    print(f"RMS of |a| - g over the positions: {np.sqrt(np.mean(np.square(before))):.4f} "
          f"m/s² before, {np.sqrt(np.mean(np.square(after))):.5f} m/s² after")

    fig, ax = plt.subplots(figsize=(8, 4))
    k = np.arange(1, len(after) + 1)
    ax.plot(k, np.array(before) * 1e3, "o", label="before (nominal scale)")
    ax.plot(k, np.array(after) * 1e3, "s", label="after calibration")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("static position")
    ax.set_ylabel("|a| − g (mm/s²)")
    ax.set_title("Xsens MTi, imu_tk's recording: residuals per position")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out_png, dpi=100)
    print(f"wrote {out_png}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "xsens_residuals.png")
