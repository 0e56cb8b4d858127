#!/usr/bin/python3
"""The paper's PI loop on a velocity-source stage, linearised in steady sliding: margins.

Around steady sliding at speed v0 the stage is
    v' = p (v_f(u_d) - v) - g(s),  T_m s' = |v| - s,  T_l u_d' = u_h - u_d,
so small deviations see
    G(s) = x/u = c k p / (s (T_l s + 1) (s + p + g'(v0) / (T_m s + 1)))
with k = dv_f/du at the operating point (the speed map's local slope), g' the Stribeck slope
(negative at low speed), c the drive hysteresis' small-signal factor 1 - sum(w) (1 without it:
a reversal smaller than every play band leaves every operator frozen). The loop is sampled
exactly (zero-order hold, scipy.signal.cont2discrete), read at x_k, PI law
u_k = Kp e_k + Ki Ts sum(e), applied on [t_k, t_k+1). Margins from L(e^{jwTs}) on a fine
grid up to the Nyquist frequency.

  /usr/bin/python3 experiments/stages/loop_margins.py STAGE [--rates 1000,10000]
      [--speeds 5,10,20,30,45,60] [--no-hysteresis-factor]
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy import signal

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from f4_motion import load_stage  # noqa: E402

KP, KI = 19000.0, 660000.0


def stage_json(spec):
    return json.loads(load_stage(spec).to_json())


def rail_g(rail, s):
    fc, fs, vs = rail["coulomb_mps2"], rail["static_mps2"], rail["stribeck_velocity_mps"]
    return fc + (fs - fc) * math.exp(-(s / vs) ** 2)


def rail_dg(rail, s):
    fc, fs, vs = rail["coulomb_mps2"], rail["static_mps2"], rail["stribeck_velocity_mps"]
    return -2 * (fs - fc) * s / vs ** 2 * math.exp(-(s / vs) ** 2)


def map_slope(motor, vf, direction):
    """dv_f/du where the speed map (one direction) reaches |v_f| = vf; [m/(s V)]."""
    u_in, v_out = motor["speed_map_in_v"], motor["speed_map_out_mps"]
    if direction > 0:
        us = [motor["dead_zone_forward_v"]] + [u for u in u_in if u > 0]
        vs = [0.0] + [v for u, v in zip(u_in, v_out) if u > 0]
    else:
        us = [motor["dead_zone_backward_v"]] + [-u for u in u_in if u < 0][::-1]
        vs = [0.0] + [-v for u, v in zip(u_in, v_out) if u < 0][::-1]
    for i in range(1, len(us)):
        if vf <= vs[i] or i == len(us) - 1:
            slope = (vs[i] - vs[i - 1]) / (us[i] - us[i - 1])
            return slope, us[i - 1] + (vf - vs[i - 1]) / slope
    raise ValueError


def plant(j, v0, direction, hysteresis_factor=True):
    motor, rail, drive = j["motor"], j["rail"], j["drive"]
    p = motor["pole_per_s"]
    if motor.get("thrust_limit_mps2"):
        raise SystemExit("thrust limit: not linearised here")
    vf = v0 + rail_g(rail, v0) / p
    k, u0 = map_slope(motor, vf, direction)
    c = 1.0
    h = drive.get("hysteresis")
    if h and hysteresis_factor:
        c = 1 - sum(h["weights"])
    gp = rail_dg(rail, v0)
    tl, tm = drive["lag_time_constant_s"], rail.get("memory_time_s", 0.0)
    # numerator / denominator in s (highest power first)
    num = np.array([c * k * p])
    # (s + p + gp/(tm s + 1)) * (tm s + 1) = tm s^2 + (1 + p tm) s + (p + gp)
    inner = np.array([tm, 1 + p * tm, p + gp]) if tm > 0 else np.array([1.0, p + gp])
    num = np.polymul(num, [tm, 1.0]) if tm > 0 else num
    den = np.polymul(np.polymul([1.0, 0.0], [tl, 1.0] if tl > 0 else [1.0]), inner)
    return num, den, {"k_mps_per_v": k, "u0_v": u0 * direction, "g_slope_per_s": gp, "c": c}


def margins(num, den, ts):
    numd, dend, _ = signal.cont2discrete((num, den), ts, method="zoh")
    numd = np.trim_zeros(np.atleast_1d(np.squeeze(numd)), "f")
    w = np.geomspace(0.1, math.pi / ts, 200000)
    z = np.exp(1j * w * ts)
    G = np.polyval(numd, z) / np.polyval(dend, z)
    C = KP + KI * ts / (1 - 1 / z)
    L = C * G
    mag = np.abs(L)
    ph = np.unwrap(np.angle(L))
    out = {"crossover_hz": float("nan"), "pm_deg": float("nan"), "gm": float("nan"),
           "phase_crossover_hz": float("nan")}
    idx = np.nonzero((mag[:-1] >= 1) & (mag[1:] < 1))[0]
    if len(idx):
        i = idx[-1]
        out["crossover_hz"] = float(w[i] / 2 / math.pi)
        out["pm_deg"] = float((180 + ph[i] * 180 / math.pi + 180) % 360 - 180)
    turns = np.floor((ph + math.pi) / (2 * math.pi))
    idx = np.nonzero(turns[1:] < turns[:-1])[0]
    if len(idx):
        i = idx[0]
        out["phase_crossover_hz"] = float(w[i] / 2 / math.pi)
        out["gm"] = float(1 / mag[i])
    # closed-loop poles: the largest |z| (stable when < 1)
    # C(z) = ((Kp + Ki Ts) z - Kp) / (z - 1)
    numL = np.polymul(np.polyadd(np.array([KP + KI * ts, 0.0]), np.array([-KP])), numd)
    denL = np.polymul([1.0, -1.0], dend)
    char = np.polyadd(denL, numL)
    poles = np.roots(char)
    out["max_pole_mag"] = float(np.max(np.abs(poles)))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stage")
    ap.add_argument("--rates", default="1000,10000")
    ap.add_argument("--speeds", default="5,10,20,30,45,60", help="operating speeds [mm/s]")
    ap.add_argument("--no-hysteresis-factor", action="store_true")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    j = stage_json(a.stage)
    rows = []
    for direction in (+1, -1):
        for v in [float(x) * 1e-3 for x in a.speeds.split(",")]:
            num, den, info = plant(j, v, direction, not a.no_hysteresis_factor)
            for rate in [float(x) for x in a.rates.split(",")]:
                m = margins(num, den, 1 / rate)
                rows.append({"direction": direction, "v_mmps": v * 1e3, "rate_hz": rate,
                             **info, **m})
    if a.json:
        print(json.dumps(rows))
        return
    print(f"{a.stage}: PI Kp {KP:g} V/m, Ki {KI:g} V/(m s), linearised in steady sliding")
    print("dir  v[mm/s]  u0[V]   k[m/(s V)]  g'[1/s]  rate[Hz]  crossover[Hz]  PM[deg]  GM    "
          "max|pole|")
    for r in rows:
        print(f"{'+' if r['direction'] > 0 else '-'}   {r['v_mmps']:6.1f}  {r['u0_v']:6.3f}  "
              f"{r['k_mps_per_v']:8.4f}  {r['g_slope_per_s']:8.1f}  {r['rate_hz']:7.0f}  "
              f"{r['crossover_hz']:10.1f}  {r['pm_deg']:8.1f}  "
              f"{r['gm']:5.2f}  {r['max_pole_mag']:.4f}")


if __name__ == "__main__":
    main()
