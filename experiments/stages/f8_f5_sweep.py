#!/usr/bin/python3
"""The "F8 with F5" search of docs/virtual_stage.md: stage candidates made of candidate C
(C.json) plus asymmetric play operators and the creep's loop share, screened by F8 at seed 1,
then F5 over seeds and the other required facts at seed 1.

Each candidate's dead zones and knots move by the lag a held voltage keeps,
(1 - k_l) sum(w_i r_i) (1 +/- alpha), as StageParameters::SetDriveHysteresis and SetDriveCreep
do, so the pulse plateaus (F1, F2) stay the paper's.

  /usr/bin/python3 experiments/stages/f8_f5_sweep.py OUT_DIR [--seeds 1-12] [--jobs 2]
      [--only NAME,NAME] [--f7]

writes OUT_DIR/NAME.json (the stage file) and OUT_DIR/NAME.facts.json, and prints the doc's
table (one row per candidate that meets F8 at seed 1, ordered by F5's count). About 25 min on
2 cores for every candidate (F5 over 12 seeds is 2-4 min a candidate). With --f7 F7 runs over
the seeds beside F5 (the typical network adds about a third) and a second table gives F7's count
and the four MSEs: issue #28's candidate table (mechanism, parameters, F4 ripple, F5 and F7 counts
over the seeds, the four MSEs).
"""
import argparse
import json
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from candidates import held_lag  # noqa: E402  (the lag a held voltage keeps, per direction)

SYSID = os.path.join(HERE, "..", "..", "build", "apps", "sysid")
PLAY = {"H0": [0.03, 0.06, 0.12], "H1": [0.05, 0.1, 0.2], "H2": [0.1, 0.2, 0.3],
        "H5": [0.15, 0.3, 0.45]}


def candidates():
    """name -> (operators, weight, alpha, loop share, T_c [s]): the grid, then the ten
    candidates around the first grid's best."""
    c = {}
    for fam in ("H1", "H2", "H5"):
        for w in (0.08, 0.12, 0.16, 0.2):
            for kl in (0.0, 0.3, 0.5, 0.7):
                for tc in (0.04, 0.1):
                    if kl == 0 and tc != 0.04:
                        continue  # no creep: T_c does nothing
                    c[f"{fam}-w{w:g}-kl{kl:g}-tc{tc * 1000:g}"] = (fam, w, 0.3, kl, tc)
    for fam, w, alpha, kl, tc in [("H1", 0.16, 0.0, 0.3, 0.04), ("H1", 0.16, -0.3, 0.3, 0.04),
                                  ("H1", 0.16, 0.6, 0.3, 0.04), ("H1", 0.18, 0.0, 0.3, 0.04),
                                  ("H1", 0.16, 0.3, 0.3, 0.07), ("H1", 0.16, 0.3, 0.4, 0.07),
                                  ("H1", 0.18, 0.3, 0.4, 0.07), ("H1", 0.14, 0.3, 0.2, 0.04),
                                  ("H0", 0.2, 0.3, 0.3, 0.04), ("H0", 0.25, 0.3, 0.3, 0.04)]:
        c[f"{fam}-w{w:g}-a{alpha:g}-kl{kl:g}-tc{tc * 1000:g}"] = (fam, w, alpha, kl, tc)
    return c


def stage_file(name, fam, w, alpha, kl, tc):
    s = json.load(open(os.path.join(HERE, "C.json")))
    s["name"] = "F8/F5 candidate " + name
    r = PLAY[fam]
    h = {"thresholds_v": r, "weights": [w] * len(r), "rate_weights_s_per_v": [0] * len(r),
         "rate_time_constant_s": 0.01, "asymmetry": alpha}
    # The creep's loop share relaxes that part of the lag while the voltage is held.
    rising, falling = (1 - kl) * held_lag(h, True), (1 - kl) * held_lag(h, False)
    m = s["motor"]
    m["dead_zone_forward_v"] -= rising
    m["dead_zone_backward_v"] -= falling
    m["speed_map_in_v"] = [u - rising if u > 0 else u + falling for u in m["speed_map_in_v"]]
    s["drive"]["hysteresis"] = h
    s["drive"]["creep"] = {"voltage_share": 0.0, "loop_share": kl, "time_constant_s": tc}
    return s


def seed1_cells(r):
    """The two cells both tables share: the verdict of F1-F4 and F6 at seed 1, and F4's ripple
    in motion at 0.5 / 1 Hz [um]."""
    failed = [k for k in ("F1", "F2", "F3", "F4", "F6") if not r[k]["met"]]
    f4 = re.search(r"in motion ([\d.]+) um.*in motion ([\d.]+) um", r["F4"]["virtual"])
    return ("met" if not failed else "fail: " + ", ".join(failed),
            f"{f4.group(1)} / {f4.group(2)}")


def span(xs):
    """min-max of a list, or the one value when they are equal (3 significant digits)."""
    return f"{min(xs):.3g}" if min(xs) == max(xs) else f"{min(xs):.3g}-{max(xs):.3g}"


def facts(path, ids, seeds=None):
    cmd = [SYSID, "stage", "facts", "--stage", path, "--facts", ids, "--json", "--threads", "1"]
    cmd += ["--seeds", seeds] if seeds else []
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    return {f["id"]: f for f in json.loads(out)["facts"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--seeds", default="1-12")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="", help="comma-separated candidate names")
    ap.add_argument("--f7", action="store_true", help="F7 over the seeds too, and its table")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    cands = candidates()
    if a.only:
        cands = {n: cands[n] for n in a.only.split(",")}

    def run(item):
        name, spec = item
        path = os.path.join(a.out, name + ".json")
        with open(path, "w") as f:
            json.dump(stage_file(name, *spec), f, indent=1)
        r = facts(path, "F1,F2,F3,F4,F6,F8")
        if r["F8"]["met"]:
            r.update(facts(path, "F5,F7" if a.f7 else "F5", a.seeds))
        with open(os.path.join(a.out, name + ".facts.json"), "w") as f:
            json.dump(r, f, indent=1)
        print(f"{name}: F8 {'met' if r['F8']['met'] else 'not met'}", file=sys.stderr, flush=True)
        return name, spec, r

    with ThreadPoolExecutor(a.jobs) as ex:
        results = [x for x in ex.map(run, cands.items()) if "F5" in x[2]]
    results.sort(key=lambda x: (-x[2]["F5"]["met_count"], x[0]))
    for name, (fam, w, alpha, kl, tc), r in results:
        verdict, f4 = seed1_cells(r)
        v8 = r["F8"]["virtual"]
        a8 = re.search(r"\+1.4 V [\d.]+ mm/s \(([\d.]+) %\), -1.9 V [\d.]+ mm/s \(([\d.]+) %\)", v8)
        c8 = re.search(r"\(x ([\d.]+)\)", v8)
        d8 = re.search(r"\(d\).*\(([-+][\d.]+) %\)", v8)
        f5 = r["F5"]
        print(f"| {name} | {'/'.join(f'{x:g}' for x in PLAY[fam])} | {w:g} | {alpha:g} | "
              f"{kl:g} / {tc * 1000:g} | {verdict} | "
              f"{f4} | {a8.group(1)} / {a8.group(2)}, x{c8.group(1)}, "
              f"{d8.group(1)} % | {f5['met_count']} ({', '.join(map(str, f5['met_seeds']))}) |")
    if a.f7:
        print()
        print("| candidate | F1-F4, F6 at seed 1 | F4 in motion [um] | F5 count | F7 count | "
              "typical train / test [V^2] | dominant train / test [V^2] | typical test / train |")
        print("|---|---|---|---|---|---|---|---|")
        for name, _, r in results:
            verdict, f4 = seed1_cells(r)
            mse = [[float(x) for x in re.findall(r"train ([\d.]+), test ([\d.]+)", v)[k]]
                   for v in r["F7"]["virtual"] for k in (0, 1)]
            typ, dom = mse[0::2], mse[1::2]  # per seed: [train, test]
            ratio = [t[1] / t[0] for t in typ]
            print(f"| {name} | {verdict} | {f4} | {r['F5']['met_count']} | "
                  f"{r['F7']['met_count']} | {span([t[0] for t in typ])} / "
                  f"{span([t[1] for t in typ])} | {span([d[0] for d in dom])} / "
                  f"{span([d[1] for d in dom])} | {span(ratio)} |")


if __name__ == "__main__":
    main()
