"""A NumPy peer of sysid.dominance for the benchmark (no SciPy function does this analysis; the
shared peers in ../shared/bench/peers cover simulation, LM training and delay tuning only).

The same work as libsysid's AnalyzeDominance with central-difference motion: v and a by central
differences (second-order one-sided ends, as numpy.gradient edge_order=2), v(t - tau) by linear
interpolation, the terms over the moving part |v| >= min_speed, their rms and peaks, the ranking
and the 0.99 quantile of the pointwise ratio to the top variable."""
import numpy as np


def dominance(model, t, x, min_speed_mps=1e-3, quantile=0.99):
    dt = np.median(np.diff(t))
    v = np.gradient(x, dt, edge_order=2)
    a = np.gradient(v, dt, edge_order=2)
    vd = np.interp(t - model["tau_s"], t, v, left=np.nan)
    moving = np.isfinite(vd) & (np.abs(v) >= min_speed_mps)
    v, a, vd = v[moving], a[moving], vd[moving]
    ta = a
    tv = np.where(vd > 0, model["a1p"], model["a1n"]) * vd
    tc = np.where(v > 0, model["a2p"], -model["a2n"])
    variables = {"acceleration": ta, "velocity": tv + tc}
    rms = {k: float(np.sqrt(np.mean(t_ * t_))) for k, t_ in variables.items()}
    order = sorted(rms, key=rms.get, reverse=True)
    top = variables[order[0]]
    nz = top != 0
    ranking = []
    for k in order:
        ratio = np.abs(variables[k][nz]) / np.abs(top[nz])
        ranking.append({"variable": k, "rms": rms[k], "peak": float(np.max(np.abs(variables[k]))),
                        "ratio_to_top": rms[k] / rms[order[0]],
                        "ratio_bound": float(np.quantile(ratio, quantile, method="higher")),
                        "ratio_max": float(ratio.max())})
    return {"dominant": order[0], "margin": rms[order[0]] / rms[order[1]],
            "moving_samples": int(moving.sum()), "ranking": ranking}
