# Sourced by the export tests (export_compile.sh, export_cortex_m.sh): the model of one KIND
# written into the current folder. Needs SYSID, SRC, KIND and fail(); sets MODEL (the export's
# model arguments), PRECS (the precisions it exports in), MUTANT (a sed edit planting a bug
# in the generated C that the check must catch) and FLOAT_REFUSED (export arguments whose
# float export must be refused, or empty).
# shellcheck shell=sh
PRECS="double float"
FLOAT_REFUSED=""
SWAP='s/_kR\[\([0-9]*\)\] = {\([^,]*\), \([^,]*\),/_kR[\1] = {\3, \2,/'
case $KIND in
  friction)
    printf '{"a1p":104.0154,"a1n":117.1441,"a2p":3.1023,"a2n":6.8216,"a3":6,"tau":0.00379}' \
      > model.json
    MODEL="--model model.json --dt 1e-4"
    # tau one sample late: the delay line reads one slot further back.
    MUTANT='s/_kWhole = \([0-9]*\);/_kWhole = \1 + 1;/' ;;
  nn)
    MODEL="--nn $SRC/datasets/paper/nn24.json"
    # the output scaling dropped: y returned in normalised units.
    MUTANT='s/return \(.*\)_kOutMin + .*;/return y;/' ;;
  pi)
    "$SYSID" hysteresis fit --model pi --operators 20 "$SRC/datasets/piezo_aye_ang/piezo.csv" \
      -o pi.json >/dev/null || fail "hysteresis fit"
    MODEL="--hysteresis pi.json --dt 5e-3"
    # two operators' thresholds swapped (operators in another order).
    MUTANT=$SWAP ;;
  gpi)
    "$SYSID" hysteresis fit --model gpi --operators 10 "$SRC/datasets/piezo_aye_ang/piezo.csv" \
      -o gpi.json >/dev/null || fail "hysteresis fit"
    MODEL="--hysteresis gpi.json --dt 5e-3"
    MUTANT=$SWAP ;;
  nn-operators)
    "$SYSID" hysteresis fit --model nn-operators --operators 3 --hidden 5 --epochs 30 \
      "$SRC/datasets/piezo_aye_ang/piezo.csv" -o ops.json >/dev/null || fail "hysteresis fit"
    MODEL="--hysteresis ops.json --dt 5e-3"
    MUTANT=$SWAP ;;
  rdpi)
    # The fitted rdpi's rate weights make its inverse unstable at 200 Hz (the library refuses
    # it): a model with a stable inverse, the library's error gain 0.15 and the float bound's
    # rate gain 0.61 (docs/deploy.md).
    printf '{"kind":"rdpi","thresholds":[0.5,1.0,1.5],"weights":[2e-6,1e-6,0.5e-6],%s}' \
      '"polynomial":[4e-6],"rate_weights":[2e-10,4e-10,0,2e-10],"offset_m":-1e-4,"input_min_v":0,"input_max_v":3.6' \
      > rdpi.json
    MODEL="--hysteresis rdpi.json --dt 5e-3"
    # Five times the rate weights: the library's gain 0.76 (invertible), the float bound's 3.0.
    printf '{"kind":"rdpi","thresholds":[0.5,1.0,1.5],"weights":[2e-6,1e-6,0.5e-6],%s}' \
      '"polynomial":[4e-6],"rate_weights":[1e-9,2e-9,0,1e-9],"offset_m":-1e-4,"input_min_v":0,"input_max_v":3.6' \
      > rdpi_fast.json
    FLOAT_REFUSED="--hysteresis rdpi_fast.json --dt 5e-3"
    # the rate from the wrong samples: u_(k-2) never updated.
    MUTANT='s/  state->u2 = state->u1;//' ;;
  bouc-wen)
    "$SYSID" hysteresis fit --model bouc-wen-piezo "$SRC/datasets/piezo_aye_ang/piezo.csv" \
      -o bw.json >/dev/null || fail "hysteresis fit"
    # The piezo recording's x as the vectors (8027 samples).
    MODEL="--hysteresis bw.json --dt 5e-3 --vectors $SRC/datasets/piezo_aye_ang/piezo.csv"
    # gamma's sign flipped in the exact step.
    MUTANT='s/b = \(.*\)_kBeta + s \* sigma \* \(.*\)_kGamma;/b = \1_kBeta - s * sigma * \2_kGamma;/' ;;
  *) fail "unknown kind $KIND" ;;
esac
