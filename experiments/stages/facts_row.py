#!/usr/bin/python3
"""One table row from `sysid stage facts --json` output: which facts are met, F3's tau, F4's
ripple in motion at 0.5 / 1 Hz and F5's max |e| rows.

  /usr/bin/python3 experiments/stages/facts_row.py FACTS.json...
"""
import json
import sys

for path in sys.argv[1:]:
    j = json.load(open(path))
    facts = {f["id"]: f for f in j["facts"]}
    met = ",".join(i for i, f in facts.items() if f["met"])
    miss = ",".join(i for i, f in facts.items() if not f["met"] and f.get("required", True))
    vals = {}
    for f in facts.values():
        vals.update(f.get("values", {}))
    def g(key, scale=1e3, fmt="{:.4f}"):
        for k, v in vals.items():
            if k.startswith(key):
                return fmt.format(v * scale)
        return "?"
    f4 = "{} / {} um".format(g("motion_ripple_m at 0.5", 1e6, "{:.2f}"),
                             g("motion_ripple_m at 1", 1e6, "{:.2f}"))
    f5 = "; ".join(" / ".join(g(f"max_error_m at {fr} Hz {s}") for s in ("none", "analytic", "nn"))
                   for fr in ("0.5", "1"))
    tau = g("tau_s", 1e3, "{:.2f}")
    print(f"{path}: met {met}; not met {miss or '-'}; F3 tau {tau} ms; F4 in motion {f4}; F5 {f5}")
