#!/usr/bin/python3
"""Build stage-file candidates for F4 in motion and score them with the PI alone.

A candidate is a dict of physical changes to a preset; `build(c)` returns the complete stage
JSON (as `sysid generate` writes it), with the speed map through the paper's pulse table for the
candidate's p and rail (StageParameters::SetSpeedMapThrough's rule: v_f(u_i) = v_i +
sgn(v_i) g(|v_i|) / p, T^-1 with a thrust limit), moved by the drive hysteresis' held lag
(SetDriveHysteresis), plus any extra knots near the dead zone. `score` runs F4's PI-alone
experiment (experiments/stages/f4_motion.py) at 0.5 and 1 Hz.

  /usr/bin/python3 experiments/stages/candidates.py --all | NAME...   (names: CANDIDATES)
      [--rates 1000,10000]     PI alone at each control rate (records stay 1 kHz)
  /usr/bin/python3 experiments/stages/candidates.py --write DIR --all | NAME...
      each candidate's stage file (NAME with / as _) for `sysid stage facts --stage`
"""
import argparse
import copy
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import f4_motion as F  # noqa: E402

S = F.S


def rail_g(rail, s):
    fc, fs, vs = rail["coulomb_mps2"], rail["static_mps2"], rail["stribeck_velocity_mps"]
    return fc + (fs - fc) * math.exp(-(s / vs) ** 2)


def held_lag(h, rising):
    if not h:
        return 0.0
    lag = sum(w * r for w, r in zip(h["weights"], h["thresholds_v"]))
    return lag * (1 + h["asymmetry"] if rising else 1 - h["asymmetry"])


def build(c):
    """The complete stage JSON of candidate `c` (a dict; see CANDIDATES)."""
    base = json.loads(F.load_stage(c.get("base", "virtual")).to_json())
    j = copy.deepcopy(base)
    j["name"] = "F4 candidate " + c.get("name", "?")
    rig = j["rig"]
    rate = c.get("rate", rig.get("control_rate_hz", rig.get("sample_rate_hz")))
    for k in ("sample_rate_hz", "control_rate_hz", "record_rate_hz"):
        rig.pop(k, None)
    if rate == 1000:
        rig["sample_rate_hz"] = 1000.0
    else:
        rig["control_rate_hz"] = float(rate)
        rig["record_rate_hz"] = 1000.0
    # keep the key order of a written stage file: sample/control rates first
    j["rig"] = dict(sorted(rig.items(), key=lambda kv: 0 if "rate" in kv[0] else 1))
    if "tl" in c:
        j["drive"]["lag_time_constant_s"] = c["tl"]
    motor, rail = j["motor"], j["rail"]
    # Dead zones in u_h coordinates before the hysteresis moves them (the base's are moved).
    h_old = j["drive"].get("hysteresis")
    dzf = motor["dead_zone_forward_v"] + held_lag(h_old, True)
    dzb = motor["dead_zone_backward_v"] + held_lag(h_old, False)
    if "dz" in c:
        dzf, dzb = c["dz"]
    if "p" in c:
        motor["pole_per_s"] = c["p"]
    if "L" in c:
        motor["thrust_limit_mps2"] = c["L"]
    rail.update(c.get("rail", {}))
    h = c.get("hyst", h_old)
    if h is None:
        j["drive"].pop("hysteresis", None)
    else:
        j["drive"]["hysteresis"] = h
    lr, lf = held_lag(h, True), held_lag(h, False)
    p = motor["pole_per_s"]
    L = motor.get("thrust_limit_mps2", 0)
    droop = (lambda f: L * math.atanh(f / L)) if L else (lambda f: f)
    knots = []
    for u, v in F.PAPER_PULSES:
        vf = v + math.copysign(droop(rail_g(rail, abs(v))), v) / p
        knots.append((u - lr if u > 0 else u + lf, vf))
    for u, vf in c.get("knots", []):  # extra knots, in u_h coordinates (no hysteresis shift)
        knots.append((u - lr if u > 0 else u + lf, vf))
    knots.sort()
    motor["dead_zone_forward_v"] = dzf - lr
    motor["dead_zone_backward_v"] = dzb - lf
    motor["speed_map_in_v"] = [k[0] for k in knots]
    motor["speed_map_out_mps"] = [k[1] for k in knots]
    text = json.dumps(j, indent=2)
    S.StageParameters.from_json(text, c.get("name", "candidate")).validate()
    return text


def stage(c):
    return S.StageParameters.from_json(build(c), c.get("name", "candidate"))


def score(c, rates=None, seed=1):
    out = {}
    for rate in rates or [c.get("rate", 10000)]:
        cc = dict(c, rate=rate)
        p = stage(cc)
        for f in (0.5, 1.0):
            o = F.analyse(p, f, seed)
            out[(rate, f)] = (o["rms_um"], o["peaks"][0][0], o["max_e_mm"],
                              o["onset"][0] / (o["rms_um"] * 1e-6) if o["rms_um"] else 0,
                              o["rms_after_breakaway_um"])
    return out


# C: the 10 kHz loop with 1 kHz records and a 0.1 ms driver lag (docs/virtual_stage.md).
C = {"rate": 10000, "tl": 1e-4}


def _c(**kw):
    return dict(C, **kw)


def _creep(v_mps, dz, fs, fc=0.6):
    """A creep segment: v_f rises slowly from the dead zone to v_mps at +1.15 / -1.65 V (the
    default's dead-zone edges), then steeply to the first pulse point; rail without
    (fs = fc) or with a small Stribeck step."""
    return _c(dz=list(dz), knots=[[1.15, v_mps], [-1.65, -v_mps]],
              rail={"static_mps2": fs, "coulomb_mps2": fc})


def _PLAY(thresholds_v):
    """Symmetric, rate-free drive hysteresis, weight 0.2 per operator."""
    n = len(thresholds_v)
    return {"thresholds_v": thresholds_v, "weights": [0.2] * n, "rate_weights_s_per_v": [0.0] * n,
            "rate_time_constant_s": 0.01, "asymmetry": 0.0}


# Every candidate of docs/virtual_stage.md's "F4 at 1 Hz" table, in its order.
CANDIDATES = {
    "A": {"rate": 1000},
    "C": dict(C),
    "H2": {"base": "drive-hysteresis-static"},
    "C-dz1.15/1.45": _c(dz=[1.15, 1.45]),
    "C-dz1.0/1.65": _c(dz=[1.0, 1.65]),
    "C-dz1.05/1.5": _c(dz=[1.05, 1.5]),
    "C-Fs1": _c(rail={"static_mps2": 1.0}),
    "C-Fs6": _c(rail={"static_mps2": 6.0, "stribeck_velocity_mps": 0.02}),
    "C-Fc1.5": _c(rail={"coulomb_mps2": 1.5}),
    "C-Tm0": _c(rail={"memory_time_s": 0.0}),
    "C-Tm60": _c(rail={"memory_time_s": 0.06}),
    "C-p450": _c(p=450),
    "C-knot-convex": _c(knots=[[1.2, 0.010], [-1.7, -0.008]]),
    "C-knot-concave": _c(knots=[[1.2, 0.035], [-1.7, -0.028]]),
    "D0.8/1.3": _c(dz=[0.8, 1.3]),
    "D0.6/1.3": _c(dz=[0.6, 1.3]),
    "D0.4/1.0": _c(dz=[0.4, 1.0]),
    "D0.2/0.5": _c(dz=[0.2, 0.5]),
    "R1.15/0.6-Fs1": _c(dz=[1.15, 0.6], rail={"static_mps2": 1.0}),
    "K5-Fs1-dz0.3/0.6": _creep(0.005, (0.3, 0.6), 1.0),
    "K5-Fs1-dz0.6/1.0": _creep(0.005, (0.6, 1.0), 1.0),
    "K8-Fs1-dz0.6/1.0": _creep(0.008, (0.6, 1.0), 1.0),
    "K8-Fs1.5-dz0.3/0.6": _creep(0.008, (0.3, 0.6), 1.5),
    "K8-Fs1.5-dz0.6/1.0": _creep(0.008, (0.6, 1.0), 1.5),
    "K8-Fs1.5-dz0.6/1.0-wide": dict(
        _creep(0.008, (0.6, 1.0), 1.5),
        knots=[[1.15, 0.008], [1.22, 0.010], [-1.65, -0.008], [-1.72, -0.010]]),
    "K8@1.2-Fs1.5-dz0.6/1.0": dict(_creep(0.008, (0.6, 1.0), 1.5),
                                   knots=[[1.2, 0.008], [-1.7, -0.008]]),
    "K10-Fs2-dz0.6/1.0": _creep(0.010, (0.6, 1.0), 2.0),
    "K8-Fs1.5-dz0.8/1.2": _creep(0.008, (0.8, 1.2), 1.5),
    "S3-dz0.3/0.6": _creep(0.003, (0.3, 0.6), 0.6),
    "S3-dz0.6/1.0": _creep(0.003, (0.6, 1.0), 0.6),
    "S3-dz0.7/1.0": _creep(0.003, (0.7, 1.0), 0.6),
    "S3-dz0.6/1.1": _creep(0.003, (0.6, 1.1), 0.6),
    "S3-dz0.65/1.0": _creep(0.003, (0.65, 1.0), 0.6),
    "S3-dz0.7/1.05": _creep(0.003, (0.7, 1.05), 0.6),
    "S3.1-dz0.7/1.0": _creep(0.0031, (0.7, 1.0), 0.6),
    "S3-Fs0.7-dz0.7/1.0": _creep(0.003, (0.7, 1.0), 0.7),
    "S4-dz0.6/1.0": _creep(0.004, (0.6, 1.0), 0.6),
    "M4-Fs0.9-dz0.6/1.0": _creep(0.004, (0.6, 1.0), 0.9),
    "M5-Fs0.9-dz0.6/1.0": _creep(0.005, (0.6, 1.0), 0.9),
    # The ceramic's play operators with a large total weight (small-signal gain 0.2): they add
    # a backlash-like lag and ring more (tried to quiet the 1 kHz loop).
    "S3-dz0.7/1.05+PI0.8-small": dict(_creep(0.003, (0.7, 1.05), 0.6),
                                      hyst=_PLAY([0.02, 0.04, 0.06, 0.08])),
    "S3-dz0.7/1.05+PI0.8": dict(_creep(0.003, (0.7, 1.05), 0.6),
                                hyst=_PLAY([0.05, 0.1, 0.15, 0.2])),
    "C+PI0.8": dict(_c(), hyst=_PLAY([0.05, 0.1, 0.15, 0.2])),
}
for _n, _c_ in CANDIDATES.items():
    _c_["name"] = _n


def file_name(name):
    return name.replace("/", "_") + ".json"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("names", nargs="*")
    ap.add_argument("--json", help="candidates as a JSON list of dicts")
    ap.add_argument("--rates", default="1000,10000")
    ap.add_argument("--write", help="write each candidate's stage file NAME.json into DIR")
    ap.add_argument("--all", action="store_true", help="every candidate in CANDIDATES")
    a = ap.parse_args()
    cands = [CANDIDATES[n] for n in (list(CANDIDATES) if a.all else a.names)]
    if a.json:
        cands += json.loads(a.json)
    for c in cands:
        if a.write:
            with open(os.path.join(a.write, file_name(c["name"])), "w") as f:
                f.write(build(c) + "\n")
            continue
        try:
            res = score(c, [float(r) for r in a.rates.split(",")])
        except Exception as e:  # an invalid stage: say why and go on
            print(f"{c['name']:28s} invalid: {e}", flush=True)
            continue
        cells = "  ".join(f"{int(rate)}Hz: {res[(rate, .5)][0]:5.2f}/{res[(rate, 1.)][0]:5.2f} um "
                          f"[after breakaway {res[(rate, .5)][4]:.2f}/{res[(rate, 1.)][4]:.2f}] "
                          f"({res[(rate, .5)][1]:.0f}/{res[(rate, 1.)][1]:.0f} Hz; onset "
                          f"{res[(rate, 1.)][3]*100:.0f}%; max e {res[(rate, .5)][2]:.4f}/"
                          f"{res[(rate, 1.)][2]:.4f} mm)"
                          for rate in sorted({k[0] for k in res}))
        print(f"{c['name']:28s} {cells}", flush=True)


if __name__ == "__main__":
    main()
