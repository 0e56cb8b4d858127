#!/usr/bin/env python3
"""Helpers of experiments/hysteresis_benchmark.sh (standard library only).

  hysteresis_score.py split REC.csv FRACTION TRAIN.csv REF.csv
      TRAIN.csv: the header and the first FRACTION of the rows (t, u, x);
      REF.csv:   every row as the reference t, x (for `sysid hysteresis invert`).
  hysteresis_score.py score REC.csv FRACTION SIM.csv INV.csv
      prints "fwd_rms_m fwd_nrmse inv_rms_v inv_nrmse" over the rows after the split:
      forward  e = x_model - x [m], NRMSE = RMS(e) / std(x);
      inverse  e = u_inverse - u [V], NRMSE = RMS(e) / std(u);
      a missing INV.csv (model not invertible) prints nan for the inverse.
  hysteresis_score.py erms TEST.csv SIM.csv
      prints e_RMS = sqrt(mean((x_model - x)^2)) [m] of SIM.csv's x_model against TEST.csv's
      x, row by row (the Bouc–Wen benchmark's measure).
"""
import csv
import math
import sys


def read(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, body = rows[0], rows[1:]
    return {name: [float(r[i]) for r in body] for i, name in enumerate(header)}


def rms_and_nrmse(model, measured):
    n = len(measured)
    e = math.sqrt(sum((a - b) ** 2 for a, b in zip(model, measured)) / n)
    mean = sum(measured) / n
    std = math.sqrt(sum((b - mean) ** 2 for b in measured) / n)
    return e, e / std


def main():
    if sys.argv[1] == "erms":
        x = read(sys.argv[2])["x"]
        xm = read(sys.argv[3])["x_model"]
        if len(x) != len(xm):
            sys.exit(f"hysteresis_score.py: {len(x)} test rows, {len(xm)} simulated rows")
        print(f"{math.sqrt(sum((a - b) ** 2 for a, b in zip(xm, x)) / len(x)):.4g}")
        return
    cmd, rec, fraction = sys.argv[1], sys.argv[2], float(sys.argv[3])
    data = read(rec)
    n = len(data["t"])
    split = int(round(fraction * n))
    if cmd == "split":
        with open(sys.argv[4], "w") as f:
            f.write("t,u,x\n")
            for k in range(split):
                f.write(f"{data['t'][k]!r},{data['u'][k]!r},{data['x'][k]!r}\n")
        with open(sys.argv[5], "w") as f:
            f.write("t,x\n")
            for k in range(n):
                f.write(f"{data['t'][k]!r},{data['x'][k]!r}\n")
        return
    sim = read(sys.argv[4])["x_model"]
    fwd = rms_and_nrmse(sim[split:], data["x"][split:])
    try:
        inv_u = read(sys.argv[5])["u"]
        inv = rms_and_nrmse(inv_u[split:], data["u"][split:])
    except (OSError, IndexError, KeyError):
        inv = (float("nan"), float("nan"))
    # NRMSE with 6 digits: the script rounds it again to 0.01 %, and a 4-digit value rounded
    # twice can land on the other side (2.2154 % -> 0.02215 -> 2.21 %).
    print(f"{fwd[0]:.4g} {fwd[1]:.6g} {inv[0]:.4g} {inv[1]:.6g}")


if __name__ == "__main__":
    main()
