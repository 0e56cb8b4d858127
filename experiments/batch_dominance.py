#!/usr/bin/env python3
"""Dominance analysis over a folder of recordings: one table (CSV) and one plot (PNG).

    python3 experiments/batch_dominance.py datasets/virtual -o dominance_out

The model comes from --model M.json, or is identified from the folder's pulse recordings
(pulses*.csv: the paper's pulse least squares, then delay tuning). Every other *.csv with t, u
and x (or v) is analysed: the rms of each inverse-model term [m/s^2] over the moving part, the
dominant variable and its margin. --scheduler ADDRESS runs the batch on a Dask cluster; by
default it runs on local threads.
"""
import argparse
import os
import pathlib
import sys
import tempfile

import sysid


def identify_model(folder):
    pulses = sorted(folder.glob("pulses*.csv"))
    if not pulses:
        sys.exit(f"batch_dominance: no --model and no pulses*.csv in {folder} to identify one")
    recs = [sysid.read_recording(p) for p in pulses]
    model = sysid.identify_pulses(recs).model
    tuned = sysid.tune_delay(model, recs)
    m = tuned.model
    print(f"model from {len(pulses)} pulse recording(s): a1p {m.a1p:.6g} a1n {m.a1n:.6g} 1/s, "
          f"a2p {m.a2p:.6g} a2n {m.a2n:.6g} m/s^2, a3 {m.a3:.6g} m/(s^2 V), tau {m.tau_s:.4g} s",
          file=sys.stderr)
    return tuned.model


def write_atomically(path, write):
    """write(tmp_path) then rename: a reader never sees a partial file."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=path.suffix)
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def plot(table, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rms = table[[c for c in table.columns if c.startswith("rms_")]]
    names = [pathlib.Path(s).stem for s in table["source"]]
    fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(names)), 4))
    width = 0.8 / max(1, rms.shape[1])
    for i, col in enumerate(rms.columns):
        ax.bar([k + i * width for k in range(len(names))], rms[col], width, label=col[4:])
    ax.set_xticks([k + 0.4 - width / 2 for k in range(len(names))], names, rotation=30,
                  ha="right")
    ax.set_yscale("log")
    ax.set_ylabel("term rms over the moving part [m/s^2]")
    ax.set_title("Dominant variable of the inverse model per recording")
    ax.legend()
    fig.tight_layout()
    write_atomically(path, lambda tmp: fig.savefig(tmp, format="png", dpi=100))
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", type=pathlib.Path, help="folder of recording CSVs")
    ap.add_argument("-o", "--output", type=pathlib.Path, default=pathlib.Path("."),
                    help="output folder for dominance.csv and dominance.png (created)")
    ap.add_argument("--model", help="model JSON (default: identified from pulses*.csv)")
    ap.add_argument("--pattern", default="*.csv", help="recordings in the folder (glob)")
    ap.add_argument("--min-speed", type=float, default=None, help="moving part: |v| >= [m/s]")
    ap.add_argument("--threads", type=int, default=None, help="local threads (default: cores)")
    ap.add_argument("--scheduler", help="Dask scheduler address (tcp://host:8786)")
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args(argv)

    model = sysid.Model.load(a.model) if a.model else identify_model(a.folder)
    files = sorted(p for p in a.folder.glob(a.pattern) if not p.name.startswith("pulses"))
    if not files:
        sys.exit(f"batch_dominance: no recordings match {a.folder / a.pattern}")
    options = {} if a.min_speed is None else {"min_speed_mps": a.min_speed}
    client = None
    if a.scheduler:
        from distributed import Client
        client = Client(a.scheduler)
    table = sysid.batch([str(f) for f in files], model=model, client=client, threads=a.threads,
                        errors="record", **options)
    if client is not None:
        client.close()

    a.output.mkdir(parents=True, exist_ok=True)
    write_atomically(a.output / "dominance.csv", lambda tmp: table.to_csv(tmp, index=False))
    if not a.no_plot:
        plot(table.dropna(subset=["dominant"]), a.output / "dominance.png")
    shown = table[["source", "dominant", "margin", "moving_samples"] +
                  (["error"] if "error" in table else [])]
    print(shown.to_string(index=False))
    print(f"wrote {a.output / 'dominance.csv'}" +
          ("" if a.no_plot else f" and {a.output / 'dominance.png'}"), file=sys.stderr)
    return 1 if "error" in table and table["error"].notna().any() else 0


if __name__ == "__main__":
    sys.exit(main())
