#!/usr/bin/env bash
# Neural-network training speed: libsysid's LM beside the Python peers (SciPy MINPACK LM,
# NumPy LM) on the same data, starting weights and scaling, in one script.
#   bench/run_nn.sh [BUILD_DIR] [PEERS_DIR]   (default PEERS_DIR: $SYSID_PEERS or ../shared/bench/peers)
# First the kernel targets: one LM epoch by the old kernels, the generic and SIMD kernels on
# 1 and all threads, GFLOP/s against this run's Eigen dgemm rate (bench_dgemm).
# Case v  (1-24-1, P = 73): time to reach a training MSE within 1 % of the best known
#          (0.0025549, the peer README) and one epoch's cost split into its parts.
# Case va (2-120-1, P = 481): time per epoch.
# The 9-network hidden-size sweep (H = 16..32 step 2) on the same data.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
PEERS="${2:-${SYSID_PEERS:-$(cd .. && pwd)/shared/bench/peers}}"
[ -f "$PEERS/p2_data_v.csv" ] || { echo "run_nn.sh: no peer data in $PEERS" >&2; exit 1; }
PY=/usr/bin/python3
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
BEST=0.0025549

echo "== kernel targets: Eigen dgemm rate and one LM epoch (N = 20000) =="
if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo; then
  "$BUILD/bench/bench_dgemm" | tee "$TMP/dgemm.jsonl"
else
  echo '{"what":"eigen_dgemm","simd":"none","gflops_1":0,"gflops_all":0}' | tee "$TMP/dgemm.jsonl"
fi
"$BUILD/bench/bench_nn" --case epoch --data "$PEERS/p2_data_v.csv" --init "$PEERS/p2_init_v.csv" \
  --repeats 7 | tee "$TMP/epoch_v.jsonl"
"$BUILD/bench/bench_nn" --case epoch --data "$PEERS/p2_data_va.csv" --init "$PEERS/p2_init_va.csv" \
  --repeats 5 | tee "$TMP/epoch_va.jsonl"

echo "== case v: ours (lm + least-squares output layer, paper rule, Ceres) =="
"$BUILD/bench/bench_nn" --case v --data "$PEERS/p2_data_v.csv" --init "$PEERS/p2_init_v.csv" \
  --best "$BEST" --epochs 100 | tee "$TMP/ours_v.jsonl"
echo "== case v: SciPy least_squares(method='lm', x_scale='jac') (MINPACK) =="
# 400 evaluations bound the run (~1 min); the target is reached well before.
"$PY" "$PEERS/p2_nn_lm.py" --case v --peers lmjac --lm-max-nfev 400 --out "$TMP/peer_v.json" \
  > /dev/null 2> "$TMP/peer_v.log" || { cat "$TMP/peer_v.log"; exit 1; }
echo "== case va: ours =="
"$BUILD/bench/bench_nn" --case va --data "$PEERS/p2_data_va.csv" --init "$PEERS/p2_init_va.csv" \
  --epochs 5 | tee "$TMP/ours_va.jsonl"
echo "== case va: SciPy MINPACK LM and NumPy LM, 3 iterations each =="
"$PY" "$PEERS/p2_nn_lm.py" --case va --peers lm,nplm --timing-repeats 1 --timing-iters 3 \
  --out "$TMP/peer_va.json" > /dev/null 2> "$TMP/peer_va.log" || { cat "$TMP/peer_va.log"; exit 1; }
echo "== sweep H = 16:32:2, 50 epochs each, lm + least-squares output layer, all cores =="
"$BUILD/bench/bench_nn" --case sweep --data "$PEERS/p2_data_v.csv" --epochs 50 | tee "$TMP/sweep.jsonl"

"$PY" - "$TMP" "$BEST" <<'PY'
import json, sys
tmp, best = sys.argv[1], float(sys.argv[2])
target = best * 1.01
ours = [json.loads(l) for l in open(tmp + "/ours_v.jsonl")]
hit = next(o for o in ours if o["what"].endswith("to target"))
split = next(o for o in ours if o["what"] == "lm_epoch_split")
peer = json.load(open(tmp + "/peer_v.json"))["peers"][0]
reach = [t for t, m in peer["traj"] if m <= target]
print("\n=== summary ===")
dg = json.loads(open(tmp + "/dgemm.jsonl").readline())
print("Eigen dgemm (%s): %.1f GFLOP/s on 1 thread, %.1f GFLOP/s on %s threads"
      % (dg["simd"], dg["gflops_1"], dg["gflops_all"], dg.get("threads", "?")))
for name, f in (("1-24-1", "epoch_v"), ("2-120-1", "epoch_va")):
    e = json.loads(open(tmp + "/" + f + ".jsonl").readline())
    print("LM epoch %s (N=%d, P=%d, %.3g flop in J'J + J'r):" % (name, e["N"], e["P"], e["flop_per_epoch"]))
    for v in e["variants"]:
        share = ("  %5.1f %% of %d-thread dgemm" % (100 * v["gflops"] / (dg["gflops_all"] if v["threads"] > 1 else dg["gflops_1"]), v["threads"])) if dg["gflops_all"] else ""
        print("  %-20s %d thread(s): %8.2f ms  %6.1f GFLOP/s%s  max rel diff vs old %.1e"
              % (v["kernels"], v["threads"], 1e3 * v["epoch_s"], v["gflops"], share, v["max_rel_diff"]))
    fastest = e["variants"][-1]
    print("  TARGET ratio vs old kernel: %.2fx on all threads (%.2fx on 1); thread scaling %.2fx"
          % (e["speedup_vs_old_all_threads"], e["speedup_vs_old_1thread"], e["thread_scaling"]))
    if dg["gflops_all"]:
        print("  TARGET share of %s-thread dgemm rate: %.0f %%" % (dg.get("threads", "?"), 100 * fastest["gflops"] / dg["gflops_all"]))
print("case v target MSE %.7g (best known %.7g + 1 %%)" % (target, best))
print("  ours (%s): %.3f s, %d epochs" % (hit["what"], hit["wall_s"], hit["epochs"]))
if reach:
    print("  SciPy MINPACK x_scale='jac': %.3f s (%.4f s/iteration)" % (reach[0], peer["time_per_iter_s"]))
    print("  speed-up: %.1fx" % (reach[0] / hit["wall_s"]))
else:
    print("  SciPy MINPACK did not reach the target in %d evaluations (final %.6g, %.1f s)"
          % (peer["nfev"], peer["final_mse"], peer["wall_s"]))
    print("  speed-up: > %.1fx" % (peer["wall_s"] / hit["wall_s"]))
for o in ours:
    if "final_mse" in o and not o["what"].endswith("to target"):
        print("  %-30s %4d epochs  %.3f s  final MSE %.7g" % (o["what"], o["epochs"], o["wall_s"], o["final_mse"]))
parts = split["sum_of_parts_s"]
print("one LM epoch (P=%d): fused blocked %.4f s vs sum of parts %.4f s (ratio %.2f)"
      % (split["P"], split["fused_blocked_epoch_s"], parts, split["epoch_over_parts"]))
for k in ("forward_x2", "jacobian", "jtj_syrk", "cholesky"):
    print("  %-10s %5.1f %%" % (k, 100 * split["share"][k]))
print("  J'J: syrk %.4f s (%.2f GFLOP/s) vs gemm %.4f s" % (split["jtj_syrk_s"], split["syrk_gflops"], split["jtj_gemm_s"]))
va = [json.loads(l) for l in open(tmp + "/ours_va.jsonl")]
pva = json.load(open(tmp + "/peer_va.json"))["peers"]
ours_va = va[0]["time_per_epoch_s"]
print("case va (P=481) time per epoch: ours %.3f s" % ours_va)
for p in pva:
    print("  %-55s %.3f s  (ours %.1fx faster)" % (p["peer"], p["time_per_iter_s"], p["time_per_iter_s"] / ours_va))
sw = json.loads(open(tmp + "/sweep.jsonl").readline())
print("sweep of %d networks (max %d epochs each): %.2f s" % (len(sw["rows"]), sw["max_epochs"], sw["wall_s"]))
PY
