#!/usr/bin/env python3
"""NumPy/SciPy peer of libsysid's virtual piezo stack (bench/run_stack.sh): the same plant
(datasets/piezo_stack/stack.json) on the same drive as bench_stack (a 10 Hz sine, 50 - 45 cos),
through the same DAC quantisation, x noise-free (the true displacement before each sample, as
RunStackOpenLoop's x_true_m, so x_end is comparable):

  - rdpi hysteresis: a Python loop over samples, the play operators vectorised with NumPy
    (np.clip of the state vector: NumPy has no vector form of the sequential operator);
  - creep and mechanics: the exact zero-order-hold step s_(k+1) = Phi s_k + Gamma y_k,
    Phi and Gamma from scipy.linalg.expm of the augmented matrix (as integrator.method exact).

  stack_numpy_peer.py [STACK.json] [--samples N] [--repeats R]
Prints "peer method=... samples=... seconds=... samples_per_s=... x_end=..." lines.
"""
import argparse
import json
import time

import numpy as np
from scipy.linalg import expm


def discretise(p, ts):
    wn = 2 * np.pi * p["mechanics"]["resonance_hz"]
    zeta = p["mechanics"]["damping_ratio"]
    taus, kappas = p["creep"]["time_constants_s"], p["creep"]["fractions"]
    n = 2 + len(taus)
    aug = np.zeros((n + 1, n + 1))
    aug[0, 1] = 1
    aug[1, 0], aug[1, 1], aug[1, n] = -wn * wn, -2 * zeta * wn, wn * wn
    for j, (tau, kappa) in enumerate(zip(taus, kappas)):
        aug[1, 2 + j] = wn * wn
        aug[2 + j, 2 + j] = -1 / tau
        aug[2 + j, n] = kappa / tau
    e = expm(aug * ts)
    return e[:n, :n], e[:n, n]


def simulate(p, u, ts, phi, gamma):
    h = p["hysteresis"]
    r = np.array(h["thresholds_v"])
    w = np.array(h["weights_m_per_v"])
    q = np.array(h["rate_weights_m_s_per_v2"])
    p0 = h["linear_gain_m_per_v"]
    z = np.zeros_like(r)
    s = np.zeros(len(gamma))
    x = np.empty(len(u))
    for k, uk in enumerate(u):
        rho = abs(u[k - 1] - u[k - 2]) / ts if k >= 2 else 0.0
        z = np.clip(z, uk - r, uk + r)
        y = (p0 + q[0] * rho) * uk + np.dot(w + q[1:] * rho, z)
        x[k] = s[0]
        s = phi @ s + gamma * y
    return x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stack", nargs="?", default="datasets/piezo_stack/stack.json")
    ap.add_argument("--samples", type=int, default=50000)
    ap.add_argument("--repeats", type=int, default=2)
    a = ap.parse_args()
    p = json.load(open(a.stack))
    rate = p["rig"]["control_rate_hz"]
    ts = 1 / rate
    t = np.arange(a.samples) / rate
    lo, hi = p["rig"]["voltage_min_v"], p["rig"]["voltage_max_v"]
    step = (hi - lo) / (2.0 ** p["rig"]["dac_bits"] - 1)
    u = np.clip(50 - 45 * np.cos(2 * np.pi * 10 * t), lo, hi)
    u = np.minimum(hi, lo + np.round((u - lo) / step) * step)
    phi, gamma = discretise(p, ts)
    best, x = None, None
    for _ in range(a.repeats):
        t0 = time.process_time()
        x = simulate(p, u, ts, phi, gamma)
        dt = time.process_time() - t0
        best = dt if best is None else min(best, dt)
    print(f"peer method=numpy-exact samples={a.samples} seconds={best:.4g} "
          f"samples_per_s={a.samples / best:.4g} x_end={x[-1]:.9e}")


if __name__ == "__main__":
    main()
