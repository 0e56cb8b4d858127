#!/usr/bin/env python3
"""Hidden-size x seed sweep of the neural inverse model on a Dask cluster.

    python3 experiments/sweep_dask.py --train datasets/virtual/training.csv \
        --test datasets/virtual/test.csv --hidden 4:12:4 --seeds 1,2,3 --workers 2 -o sweep.csv

Each (hidden size, seed) trains one network (Levenberg-Marquardt, one thread) in a Dask task.
By default a LocalCluster of --workers processes runs here; --scheduler ADDRESS sends the tasks
to an existing cluster instead (its workers must see the CSV paths). The table has one row per
run (epochs, training/test MSE [V^2], termination); the summary averages over seeds.
"""
import argparse
import os
import sys
import tempfile

import sysid


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--train", required=True, help="training CSV (input and output columns)")
    ap.add_argument("--test", help="test CSV, reported, never trained on")
    ap.add_argument("--validation", help="validation CSV for early stopping")
    ap.add_argument("--inputs", default="v", help="comma-separated input columns (default v)")
    ap.add_argument("--output", default="u", help="target column (default u [V])")
    ap.add_argument("--hidden", default="16:32:4", help="hidden sizes FIRST:LAST:STEP or a,b,c")
    ap.add_argument("--seeds", default="1,2,3", help="comma-separated initialisation seeds")
    ap.add_argument("--max-epochs", type=int, default=200)
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    ap.add_argument("--scheduler", help="Dask scheduler address (instead of a LocalCluster)")
    ap.add_argument("-o", "--out", help="write the table as CSV (atomically)")
    a = ap.parse_args(argv)

    from distributed import Client, LocalCluster
    seeds = [int(s) for s in a.seeds.split(",")]
    paths = {k: (os.path.abspath(v) if v else None)
             for k, v in (("train", a.train), ("test", a.test), ("validation", a.validation))}
    if a.scheduler:
        cluster, client = None, Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                               dashboard_address=":0")
        client = Client(cluster)
    try:
        table = sysid.sweep_grid(paths["train"], a.hidden, seeds, validation=paths["validation"],
                                 test=paths["test"], inputs=a.inputs, output=a.output,
                                 client=client, max_epochs=a.max_epochs)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    print(table.to_string(index=False))
    summary = table.groupby("hidden")[["train_mse", "test_mse"]].mean()
    print("\nmean over seeds [V^2]:\n" + summary.to_string())
    if a.out:
        directory = os.path.dirname(os.path.abspath(a.out))
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=".sweep.", suffix=".csv")
        os.close(fd)
        try:
            table.to_csv(tmp, index=False)
            os.replace(tmp, a.out)
        except BaseException:
            os.unlink(tmp)
            raise
    return 0


if __name__ == "__main__":
    sys.exit(main())
