#!/usr/bin/env python3
"""NumPy/SciPy peer of libsysid's Bouc-Wen simulators (bench/run_bouc_wen.sh), the same model
(the benchmark's true mechanical system) on the same input:

  - solve_ivp (LSODA, rtol 1e-6) with u linear between samples (np.interp), the ODE
    m y'' + c y' + k y + z = u, z' = alpha y' - beta (gamma |y'| z + delta y' |z|);
  - the benchmark chain: FFT upsampling x20, Newmark average acceleration + trapezoidal z with
    Newton (a Python loop: NumPy has no vector form of a sequential implicit step), FIR
    decimation with scipy.signal.firwin(31, 1/r, hamming) = MATLAB fir1(30, 1/r).

  bouc_wen_numpy_peer.py REC.csv [--chain-samples N] [--repeats R]
Prints "peer method=... samples=... seconds=... samples_per_s=..." lines.
"""
import argparse
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.signal import firwin

M, C, K, ALPHA, BETA, GAMMA, DELTA = 2.0, 10.0, 5e4, 5e4, 1e3, 0.8, -1.1


def rate(v, z):
    return ALPHA * v - BETA * (GAMMA * abs(v) * z + DELTA * v * abs(z))


def simulate_ivp(u, dt, rtol):
    t = np.arange(len(u)) * dt

    def f(tt, s):
        uu = np.interp(tt, t, u)
        return [s[1], (uu - C * s[1] - K * s[0] - s[2]) / M, rate(s[1], s[2])]

    sol = solve_ivp(f, (0, t[-1]), [0.0, 0.0, 0.0], method="LSODA", t_eval=t, rtol=rtol,
                    atol=rtol * 1e-3 * np.array([1e-3, 0.2, 100.0]))
    return sol.y[0]


def newmark(uf, h):
    y = np.empty(len(uf))
    yy = v = z = 0.0
    a = uf[0] / M
    y[0] = 0.0
    j11 = 4 * M / h**2 + 2 * C / h + K
    for i in range(1, len(uf)):
        f0 = rate(v, z)
        y1, z1 = yy + h * v + 0.5 * h * h * a, z + h * f0
        for _ in range(50):
            v1 = 2 * (y1 - yy) / h - v
            a1 = 4 * (y1 - yy - h * v) / h**2 - a
            sv = np.sign(v1)
            sz = np.sign(z1)
            f1 = ALPHA * v1 - BETA * (GAMMA * abs(v1) * z1 + DELTA * v1 * abs(z1))
            dfv = ALPHA - BETA * (GAMMA * sv * z1 + DELTA * abs(z1))
            dfz = -BETA * (GAMMA * abs(v1) + DELTA * v1 * sz)
            r1 = M * a1 + C * v1 + K * y1 + z1 - uf[i]
            r2 = z1 - z - 0.5 * h * (f0 + f1)
            j21, j22 = -dfv, 1 - 0.5 * h * dfz
            det = j11 * j22 - j21
            dy, dz = (r1 * j22 - r2) / det, (j11 * r2 - j21 * r1) / det
            y1 -= dy
            z1 -= dz
            if abs(dy) <= 1e-15 * (abs(y1) + h * abs(v1)) and abs(dz) <= 1e-15 * (abs(z1) + h * abs(f1)):
                break
        v1 = 2 * (y1 - yy) / h - v
        a = 4 * (y1 - yy - h * v) / h**2 - a
        yy, v, z = y1, v1, z1
        y[i] = y1
    return y


def decimate_fir(x, r):
    b = firwin(31, 1.0 / r, window="hamming")
    full = np.convolve(x, b)  # full[i + 15] = filtered x delayed by 15
    return full[15:15 + len(x)][::r]


def simulate_chain(u, dt, up=20):
    n = len(u)
    spectrum = np.fft.rfft(u)
    uf = np.fft.irfft(spectrum, n * up) * up
    y = newmark(uf, dt / up)
    for r in (2, 2, 5):
        y = decimate_fir(y, r)
    return y[:n]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("rec")
    p.add_argument("--chain-samples", type=int, default=512)
    p.add_argument("--repeats", type=int, default=1)
    a = p.parse_args()
    # sysid's CSVs open with "# ..." provenance lines, then the header: loadtxt's skiprows
    # counts the comment lines too, so drop both before parsing.
    with open(a.rec) as f:
        rows = [line for line in f if not line.startswith("#")][1:]
    data = np.loadtxt(rows, delimiter=",")
    t, u = data[:, 0], data[:, 1]
    dt = t[1] - t[0]

    def timed(name, fn, uu):
        best = 1e300
        for _ in range(a.repeats):
            t0 = time.perf_counter()
            y = fn(uu)
            best = min(best, time.perf_counter() - t0)
        print("peer method=%s samples=%d seconds=%.4f samples_per_s=%.4g y_end=%.6e"
              % (name, len(uu), best, len(uu) / best, y[-1]))

    timed("solve_ivp-lsoda-linear-rtol1e-6", lambda uu: simulate_ivp(uu, dt, 1e-6), u)
    timed("chain-newmark-x20-python", lambda uu: simulate_chain(uu, dt), u[:a.chain_samples])


if __name__ == "__main__":
    main()
