#!/usr/bin/python3
"""F4 in motion on a stage: where the high-passed tracking error's energy sits.

Runs the paper's PI alone (F4's experiment: smooth 10 mm profile, dwell 10 %, 2 cycles) on a
stage, forms F4's residual r = e - (centred 50 ms moving average of e) over the samples after
cycle 1 (as paper::MotionRippleOf), and splits r's energy into windows around each stroke's
onset (the reference leaves a dwell), its end (the reference reaches a dwell) and the rest
("steady motion" / dwell). The commands are replayed open loop (RunOpenLoop, same seed: the
same plant) to read the true velocity and the stick/slip state.

  /usr/bin/python3 experiments/stages/f4_motion.py STAGE [--freq 1] [--rate HZ] [--json]

STAGE is a stage file or a preset name; --rate overrides the control rate (records stay 1 kHz
where the rate divides by it). Units: SI, printed in um, mm/s, V, Hz.
"""
import argparse
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "build", "python"))
import sysid  # noqa: E402

S = sysid.stage
PAPER_PULSES = [(-2.5, -0.07120), (-2.3, -0.05562), (-2.1, -0.04991), (-2.0, -0.04622),
                (-1.8, -0.03393), (1.3, 0.04465), (1.5, 0.05742), (1.6, 0.06222),
                (1.7, 0.06863), (2.0, 0.08519)]


def load_stage(spec, rate_hz=None, overrides=None):
    """A stage from a file or preset name, with optional overrides (dict merged into its JSON)."""
    if os.path.exists(spec):
        text = open(spec).read()
        p = S.StageParameters.from_json(text, spec)
    else:
        p = S.StageParameters.from_json(json.dumps({"preset": spec}))
    if rate_hz or overrides:
        j = json.loads(p.to_json())
        if rate_hz:
            rig = j["rig"]
            rig.pop("sample_rate_hz", None)
            rig["control_rate_hz"] = float(rate_hz)
            rig["record_rate_hz"] = 1000.0 if rate_hz % 1000 == 0 else float(rate_hz)
        for sec, kv in (overrides or {}).items():
            j[sec].update(kv)
        p = S.StageParameters.from_json(json.dumps(j))
    return p


def moving_residual(e, rate_hz, freq_hz, window_s=0.05):
    half = int(round(0.5 * window_s * rate_hz))
    n = len(e)
    first = max(half, int(np.ceil(rate_hz / freq_hz - 1e-9)))
    last = n - half
    c = np.concatenate([[0.0], np.cumsum(e.astype(np.longdouble))])
    k = np.arange(first, last)
    mean = (c[k + half + 1] - c[k - half]) / (2 * half + 1)
    return k, e[first:last] - mean.astype(float)


def analyse(p, freq, seed=1, after_s=0.06):
    """F4's PI-alone run at `freq` [Hz] on stage `p`, and where its residual sits."""
    rate = p.sample_rate_hz
    # F4's profile: 10 mm strokes, dwell 10 % of the period at each end, 2 cycles.
    prof = S.SmoothProfileOptions(frequency_hz=freq, amplitude_m=0.01, cycles=2,
                                  sample_rate_hz=rate)
    ref = S.smooth_profile(prof)
    pi = S.PiOptions()
    res, _ = S.track_stage(p, ref, pi, None, seed)
    e = np.asarray(res.e_m)
    u = np.asarray(res.u_v)
    t = np.asarray(res.t_s)
    k, r = moving_residual(e, rate, freq)
    rms = float(np.sqrt(np.mean(r ** 2)))
    # Replay the commands open loop: the same plant, its true state (the replay's encoder must
    # equal the loop's, else the state read here is not the loop's).
    run = S.run_open_loop(p, u, seed)
    v = np.asarray(run.v_true_mps)
    replay_dx = float(np.max(np.abs(np.asarray(run.x_m) - np.asarray(res.x_m))))
    if replay_dx > 0:
        print(f"warning: the open-loop replay differs from the loop by {replay_dx:g} m",
              file=sys.stderr)
    period = 1.0 / freq
    dwell = 0.1 * period
    tm = 0.5 * period - dwell
    onsets = sorted([c * period + dwell for c in range(2)] +
                    [c * period + 2 * dwell + tm for c in range(2)])
    stuck = v == 0.0  # the rail's stuck state (a sliding stage passes v = 0 at one instant)
    tk = t[k]
    # Each stroke: onset window = the reference leaves the dwell .. the stage's breakaway
    # + after_s; motion = the rest of the stroke; dwell = the reference at rest. (A stage still
    # sliding when the reference leaves, as in a 1 kHz loop's ring, "breaks away" at once.)
    label = np.full(len(tk), 2)  # 0 onset, 1 motion, 2 dwell
    breaks = []
    for o in onsets:
        i0 = int(round(o * rate))
        i1 = min(len(v), i0 + int(0.3 * rate))
        moving = np.nonzero(~stuck[i0:i1])[0]
        ib = i0 + (moving[0] if len(moving) else 0)
        breaks.append(ib)
        tb = ib / rate
        label[(tk >= o) & (tk < o + tm)] = 1
        label[(tk >= o) & (tk < min(tb + after_s, o + tm))] = 0

    def part(mask):  # (its share of the whole RMS, the RMS inside, its share of the samples)
        return (float(np.sqrt(np.sum(r[mask] ** 2) / len(r))),
                float(np.sqrt(np.mean(r[mask] ** 2))) if mask.any() else 0.0,
                float(mask.mean()))
    near_on, motion, rest = label == 0, label == 1, label == 2
    # Periodogram of r (Hann), top peaks
    m = len(r)
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(m) / (m - 1))
    P = np.abs(np.fft.rfft(r * w)) ** 2
    f = np.arange(len(P)) * rate / m
    P[0] = 0
    order = np.argsort(P)[::-1]
    peaks = []
    for i in order:
        if all(abs(f[i] - q) > 3 for q, _ in peaks):
            peaks.append((float(f[i]), float(P[i] / P.sum())))
        if len(peaks) == 4:
            break
    # band energies
    bands = [(0, 20), (20, 50), (50, 150), (150, 500), (500, rate / 2 + 1)]
    band = [(lo, hi, float(P[(f >= lo) & (f < hi)].sum() / P.sum())) for lo, hi in bands]
    out = {"rate_hz": rate, "freq_hz": freq, "rms_um": rms * 1e6,
           "replay_max_dx_m": replay_dx,
           "onset": part(near_on), "motion": part(motion), "dwell": part(rest),
           "peaks": peaks, "bands": band,
           "max_abs_r_um": float(np.max(np.abs(r)) * 1e6),
           "t_max_r": float(tk[np.argmax(np.abs(r))]),
           "max_e_mm": float(np.max(np.abs(e)) * 1e3)}
    # per onset: time stuck after the reference leaves, e and u at breakaway, peak v
    ev = []
    for o, ib in zip(onsets, breaks):
        if o < period:
            continue
        i0 = int(round(o * rate))
        seg = slice(ib, ib + int(after_s * rate))
        inwin = (tk >= o) & (tk < ib / rate + after_s)
        ev.append({"t_onset": o, "t_break_ms": (ib - i0) / rate * 1e3,
                   "u_dwell_v": float(u[i0 - 1]), "u_break_v": float(u[ib]),
                   "e_break_um": float(e[ib] * 1e6),
                   "v_peak_mmps": float(np.max(np.abs(v[seg])) * 1e3),
                   "vref_break_mmps": float(abs(np.asarray(ref.v_mps)[ib]) * 1e3),
                   "r_rms_onset_um": float(np.sqrt(np.mean(r[inwin] ** 2)) * 1e6),
                   "stick_events": int(np.sum(np.diff(stuck[seg].astype(int)) == 1))})
    out["onsets"] = ev
    # Item 4's alternative (needs e only): leave out of the RMS each stroke's breakaway
    # transient, from the reference's departure to 50 ms (the average's width) after the
    # largest |e| of the stroke's first half (the event F5's max |e| measures).
    keep = np.ones(len(tk), dtype=bool)
    for o in onsets:
        i0, i1 = int(round(o * rate)), int(round((o + 0.5 * tm) * rate))
        ip = i0 + int(np.argmax(np.abs(e[i0:i1])))
        keep &= ~((tk >= o) & (tk < ip / rate + 0.05))
    out["rms_after_breakaway_um"] = float(np.sqrt(np.mean(r[keep] ** 2)) * 1e6)
    out["kept_fraction"] = float(keep.mean())
    # in steady motion: stick events (hunting)
    mv = np.zeros_like(t, dtype=bool)
    for o, ib in zip(onsets, breaks):
        mv |= (t >= ib / rate + after_s) & (t < o + tm)
    mv &= t >= period
    out["motion_stuck_fraction"] = float(stuck[mv].mean()) if mv.any() else 0.0
    out["motion_stick_events"] = int(np.sum(np.diff(stuck[mv].astype(int)) == 1))
    out["trace"] = (t, e, u, v, ref, k, r)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stage")
    ap.add_argument("--freq", type=float, action="append")
    ap.add_argument("--rate", type=float)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    p = load_stage(a.stage, a.rate)
    for f in a.freq or [0.5, 1.0]:
        o = analyse(p, f, a.seed)
        o.pop("trace")
        if a.json:
            print(json.dumps(o))
            continue
        print(f"{a.stage} @ {o['rate_hz']:.0f} Hz loop, {f} Hz: ripple in motion "
              f"{o['rms_um']:.2f} um (max |r| {o['max_abs_r_um']:.1f} um at t = "
              f"{o['t_max_r']:.4f} s; max |e| {o['max_e_mm']:.4f} mm; "
              f"replay max dx {o['replay_max_dx_m']:.1e} m)")
        print(f"  without the breakaway transients (departure .. peak |e| + 50 ms): "
              f"{o['rms_after_breakaway_um']:.2f} um over {o['kept_fraction']*100:.0f} % "
              f"of the samples")
        for name in ("onset", "motion", "dwell"):
            c, rr, fr = o[name]
            print(f"  {name:6s}: share of sum r^2 {c**2 / (o['rms_um']*1e-6)**2 * 100:5.1f} %  "
                  f"RMS inside {rr*1e6:6.2f} um  time share {fr*100:5.1f} %")
        print("  peaks [Hz, share]: " +
              ", ".join(f"{q:.1f} ({s*100:.1f} %)" for q, s in o["peaks"]))
        print("  bands: " +
              ", ".join(f"{lo:.0f}-{hi:.0f} Hz {s*100:.1f} %" for lo, hi, s in o["bands"]))
        print(f"  steady motion: stuck {o['motion_stuck_fraction']*100:.1f} % of samples, "
              f"{o['motion_stick_events']} stick events")
        for ev in o["onsets"]:
            print("  onset t={t_onset:.3f}: u in the dwell {u_dwell_v:.3f} V; breakaway after "
                  "{t_break_ms:.1f} ms at u={u_break_v:.3f} V, e={e_break_um:.1f} um, v_ref "
                  "{vref_break_mmps:.1f} mm/s; v peak {v_peak_mmps:.1f} mm/s in the next 60 ms "
                  "({stick_events} sticks); r RMS onset..break+60 ms "
                  "{r_rms_onset_um:.1f} um".format(**ev))


if __name__ == "__main__":
    main()
