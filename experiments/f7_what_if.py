#!/usr/bin/env python3
"""F7 what-if (docs/virtual_stage.md, "F7: what the data allow"): add a position-dependent
voltage term, 0.3 sin(2 pi x / 5 mm) V, that neither network input carries, to u of the bundled
tracking sets, and train the pipeline's two networks as the facts do (dominant: v, 24 units,
100 epochs; typical: v, a, 120 units, 60 epochs on every 2nd row; output layer re-solved).
Once on the moving rows only (|v| >= 1 mm/s), once on every row. Not a stage: a test of what
the networks make of a hidden variable, with and without the rows at rest.

usage: experiments/f7_what_if.py [DATASET_DIR]   (default datasets/virtual; needs the sysid
Python package: scripts/setup.sh installs it)"""
import pathlib
import sys

import numpy as np
import sysid

REST_SPEED_MPS = 1e-3
AMPLITUDE_V, WAVELENGTH_M = 0.3, 5e-3


def columns(rec):
    data = np.asarray(rec.data)
    return {name: data[:, i] for i, name in enumerate(rec.names)}


def subset(d, keep):
    return {k: v[keep] for k, v in d.items()}


def dataset(d, inputs):
    u = d["u"] + AMPLITUDE_V * np.sin(2 * np.pi * d["x"] / WAVELENGTH_M)
    rec = sysid.recording(t=d["t"], u=u, x=d["x"], v=d["v"], a=d["a"])
    return sysid.make_dataset(rec, inputs, "u")


def networks(train, test):
    dom = sysid.train(dataset(train, ["v"]), hidden=24, max_epochs=100, solve_output_layer=True,
                      threads=1).network
    every2 = subset(train, np.arange(len(train["t"])) % 2 == 0)
    typ = sysid.train(dataset(every2, ["v", "a"]), hidden=120, max_epochs=60,
                      solve_output_layer=True, threads=1).network
    mse = sysid.mean_squared_error
    return (mse(dom, dataset(train, ["v"])), mse(dom, dataset(test, ["v"])),
            mse(typ, dataset(train, ["v", "a"])), mse(typ, dataset(test, ["v", "a"])))


def main():
    folder = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "datasets/virtual")
    train = columns(sysid.read_recording(str(folder / "training.csv")))
    test = columns(sysid.read_recording(str(folder / "test.csv")))
    print("rows,dominant_train_v2,dominant_test_v2,typical_train_v2,typical_test_v2,"
          "typical_test_over_train")
    for label, keep in (("moving", lambda d: np.abs(d["v"]) >= REST_SPEED_MPS),
                        ("all", lambda d: np.ones(len(d["t"]), bool))):
        print(f"{label}: training and test rows", file=sys.stderr)
        dt, de, tt, te = networks(subset(train, keep(train)), subset(test, keep(test)))
        print(f"{label},{dt:.4g},{de:.4g},{tt:.4g},{te:.4g},{te / tt:.3g}", flush=True)


if __name__ == "__main__":
    main()
