#!/usr/bin/env python3
"""Python package benchmarks (issue #15), as ratios measured in one run:

 1. binding overhead: sysid.dominance over the bundled recordings from Python vs the same
    AnalyzeDominance calls in C++ (bench_dominance), both one thread, recordings in memory;
 2. batch throughput: sysid.batch dominance over N generated recordings (CSV files), a thread
    pool of 2 vs 1, and a Dask LocalCluster of 2 worker processes vs 1;
 3. the NumPy peer (bench/dominance_numpy_peer.py) vs sysid.dominance on the same recordings.

    bench/run_python.sh [BUILD_DIR] [N]
"""
import argparse
import glob
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

import sysid

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import dominance_numpy_peer  # noqa: E402


def best_of_pair(repeats, fa, fb):
    """Best times of fa and fb, run alternately so that both see the same machine load."""
    ta = tb = float("inf")
    for _ in range(repeats):
        ta = min(ta, best_of(1, fa))
        tb = min(tb, best_of(1, fb))
    return ta, tb


def best_of(repeats, fn):
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def generate(folder, n, rows, seed=1):
    """n recordings (t, u, x) of `rows` samples from the bundled virtual-stage waveforms: one of
    them repeated end to end (its kept cycles) from a random start, x scaled by 0.5..1.5 and
    1e-7 m quantised encoder noise added."""
    rng = np.random.default_rng(seed)
    base = [sysid.read_recording(p) for p in
            sorted(glob.glob(str(ROOT / "datasets/virtual/waveform_*.csv")))]
    paths = []
    for i in range(n):
        b = base[i % len(base)]
        idx = (int(rng.integers(0, b.rows)) + np.arange(rows)) % b.rows
        t = np.arange(rows) * (b["t"][1] - b["t"][0])
        x = b["x"][idx] * rng.uniform(0.5, 1.5)
        x = np.round((x + rng.normal(0, 3e-8, rows)) / 1e-7) * 1e-7
        # Written as a data logger would: t to the ms, u to the DAC's 16 bits, x on the 0.1 um
        # encoder grid (not 17 digits per cell: the parse would dominate the analysis).
        path = folder / f"gen_{i:04d}.csv"
        np.savetxt(path, np.column_stack([t, b["u"][idx], x]), fmt=["%.3f", "%.6g", "%.7f"],
                   delimiter=",", header="t,u,x", comments="")
        paths.append(str(path))
    return paths


def _warm_worker(model, path):
    import sysid  # noqa: F401  (the worker process's first import)
    sysid.batch([path], model=model, threads=1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("-n", type=int, default=1000, help="generated recordings")
    ap.add_argument("--rows", type=int, default=5000,
                    help="samples per generated recording (5 s at 1 kHz)")
    ap.add_argument("--repeats", type=int, default=9)
    a = ap.parse_args()
    build = pathlib.Path(a.build)
    model = sysid.identify_pulses(ROOT / "datasets/virtual/pulses.csv").model
    print(f"machine: {os.cpu_count()} cores; load average {os.getloadavg()[0]:.2f}")

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        model_path = tmp / "model.json"
        model.save(str(model_path))

        # 1. Binding overhead. A pass is 0.7 ms, so best of 300 (0.2 s a side): with 30, one
        # burst of another process's work could cover every pass of one side.
        bundled = sorted(glob.glob(str(ROOT / "datasets/virtual/*.csv")))
        recs = [sysid.read_recording(p) for p in bundled]
        out = subprocess.run([str(build / "bench" / "bench_dominance"), str(model_path), *bundled,
                              "--repeats", "300"], capture_output=True, text=True, check=True)
        cpp = float(out.stdout.split()[1])
        opts = sysid.DominanceOptions(threads=1)
        py, py_top = best_of_pair(
            300, lambda: [sysid._sysid.analyze_dominance(model, r, opts) for r in recs],
            lambda: [sysid.dominance(model, r, opts) for r in recs])
        print(f"\n1. binding overhead, dominance over the {len(recs)} bundled recordings "
              "(1 thread):")
        print(f"   C++ {cpp * 1e3:.3f} ms   Python sysid._sysid {py * 1e3:.3f} ms "
              f"({py / cpp:.3f}x)   sysid.dominance {py_top * 1e3:.3f} ms ({py_top / cpp:.3f}x)")

        # 2. Batch throughput.
        folder = tmp / "gen"
        folder.mkdir()
        t0 = time.perf_counter()
        paths = generate(folder, a.n, a.rows)
        mem = sysid.read_recordings(paths)
        rows = sum(r.rows for r in mem) / len(mem)
        print(f"\n2. batch dominance over {a.n} generated recordings (CSV files, {rows:.0f} rows "
              f"each on average; generated in {time.perf_counter() - t0:.1f} s)")
        t1, t2 = best_of_pair(a.repeats, lambda: sysid.batch(paths, model=model, threads=1),
                              lambda: sysid.batch(paths, model=model, threads=2))
        print(f"   threads: 1 -> {t1:.3f} s, 2 -> {t2:.3f} s: speed-up {t1 / t2:.2f}x")
        m1, m2 = best_of_pair(a.repeats, lambda: sysid.batch(mem, model=model, threads=1),
                              lambda: sysid.batch(mem, model=model, threads=2))
        print(f"   in memory (Recording objects): 1 -> {m1:.3f} s, 2 -> {m2:.3f} s: "
              f"speed-up {m1 / m2:.2f}x")
        from distributed import Client, LocalCluster
        clusters = {w: LocalCluster(n_workers=w, threads_per_worker=1, processes=True,
                                    dashboard_address=":0") for w in (1, 2)}
        clients = {w: Client(c) for w, c in clusters.items()}
        try:
            # Warm-up outside the timed region, the same for both clusters: every worker imports
            # sysid and analyses one file (client.run reaches each worker, which a small batch
            # does not guarantee), then one small batch through the scheduler.
            for client in clients.values():
                client.run(_warm_worker, model, paths[0])
                sysid.batch(paths[:16], model=model, client=client)
            d1, d2 = best_of_pair(a.repeats,
                                  lambda: sysid.batch(paths, model=model, client=clients[1]),
                                  lambda: sysid.batch(paths, model=model, client=clients[2]))
        finally:
            for w in (1, 2):
                clients[w].close()
                clusters[w].close()
        print(f"   Dask LocalCluster: 1 worker -> {d1:.3f} s, 2 workers -> {d2:.3f} s:"
              f" speed-up {d1 / d2:.2f}x")

        # 3. NumPy peer, same recordings in memory, one thread each.
        arrays = [(r["t"].copy(), r["x"].copy()) for r in mem]
        md = {k: getattr(model, k) for k in ("a1p", "a1n", "a2p", "a2n", "tau_s")}
        peer, ours = best_of_pair(a.repeats,
                                  lambda: [dominance_numpy_peer.dominance(md, t, x)
                                           for t, x in arrays],
                                  lambda: [sysid.dominance(model, r, opts) for r in mem])
        check = dominance_numpy_peer.dominance(md, *arrays[0])
        ref = sysid.dominance(model, mem[0], opts)
        print(f"\n3. NumPy peer vs sysid.dominance, {a.n} recordings in memory, 1 thread:")
        print(f"   NumPy {peer:.3f} s, sysid {ours:.3f} s: sysid {peer / ours:.1f}x faster "
              f"(same dominant: {check['dominant'] == ref.dominant}, margin {check['margin']:.6g}"
              f" vs {ref.margin:.6g})")


ROOT = HERE.parent
if __name__ == "__main__":
    main()
