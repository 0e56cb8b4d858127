#!/bin/sh
# The numbers the docs quote, checked (issue 29): runs the commands that docs/tutorial.md,
# docs/emps.md, docs/python.md, docs/robustness.md and README.md quote -- those that run in an
# empty folder against the bundled data -- and compares each number the text states with the
# number the command gives now. The quoted number is read from the doc itself (by a pattern
# around it), so editing a doc's number without the run agreeing fails, and a doc that no longer
# says the sentence fails too (update the pattern here with the doc).
#
#   [SYSID_PYTHON=/usr/bin/python3] sh scripts/check_docs.sh SYSID_EXECUTABLE SOURCE_DIR \
#       [PYTHONPATH_OF_SYSID]
#
# Tolerances (each check names its own): a number printed with d significant digits must match
# to half a unit of its last digit plus 0.1 % (the solvers' run-to-run spread across compilers
# and BLAS builds is below 0.1 %); "about N" counts get +-2 (a word, not a digit); percentages
# quoted as integers get +-1 point. Timings ("about 5 s") are machine-dependent and are not
# checked. Not run (and why): README's and docs/python.md's `sh` blocks (scripts/demo.sh,
# scripts/test.sh install and build: that is CI itself), docs/python.md's Dask block (needs a
# cluster and the user's runs/ folder), the paper-sized sweep (a minute of CPU; its warning rule
# is tested in tests/nn/under_trained_test.cpp).
#
# CTest: label "docs", about 30 s in Release on two idle cores (tutorial 6 s, refine 10 s,
# EMPS 3 s, Python tutorial 10 s). The Python parts are skipped when the package is absent
# (the sanitizer build has no Python module).
set -eu
[ $# -ge 2 ] || { echo "usage: check_docs.sh SYSID_EXECUTABLE SOURCE_DIR [PYTHONPATH]" >&2; exit 1; }
exec python3 - "$@" <<'PY'
import json, math, os, re, shutil, subprocess, sys, tempfile, time

sysid_exe = os.path.abspath(sys.argv[1])
src = os.path.abspath(sys.argv[2])
pythonpath = os.path.abspath(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[3] else ""
work = tempfile.mkdtemp(prefix="check_docs.")
failures, checks = [], 0
started = time.monotonic()

bin_dir = os.path.join(work, "bin")
os.mkdir(bin_dir)
os.symlink(sysid_exe, os.path.join(bin_dir, "sysid"))
env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ.get("PATH", ""))
if pythonpath:
    env["PYTHONPATH"] = pythonpath + os.pathsep + env.get("PYTHONPATH", "")


def folder(name):
    """A fresh folder in `work` where `datasets` is the source tree's (read only)."""
    path = os.path.join(work, name)
    os.mkdir(path)
    os.symlink(os.path.join(src, "datasets"), os.path.join(path, "datasets"))
    return path


def run(args, cwd, expect=0):
    p = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True)
    if p.returncode != expect:
        sys.stderr.write(p.stdout[-3000:] + p.stderr[-3000:])
        sys.exit(f"check_docs: `{' '.join(args)}` exited {p.returncode} (expected {expect})")
    return p


def doc(name):
    with open(os.path.join(src, name), encoding="utf-8") as f:
        return f.read()


def quoted(name, pattern):
    """The numbers the pattern's groups capture in doc `name` (whitespace in the pattern matches
    any run of blanks and line breaks)."""
    regex = re.sub(r"(\\ | )+", r"\\s+", pattern)
    m = re.search(regex, doc(name))
    if not m:
        sys.exit(f"check_docs: {name} no longer says /{pattern}/: update scripts/check_docs.sh "
                 f"with the doc")
    values = [float(g.replace("−", "-").replace(" ", "")) for g in m.groups()]
    return values if len(values) > 1 else values[0]


def digits_tolerance(text_value):
    """Half a unit of the last printed digit, plus 0.1 % (see the header)."""
    s = str(text_value)
    decimals = len(s.split(".")[1]) if "." in s else 0
    return 0.5 * 10 ** -decimals


def close(name, what, measured, stated, tolerance):
    global checks
    checks += 1
    ok = abs(measured - stated) <= tolerance + 1e-3 * abs(stated)
    line = f"{'ok  ' if ok else 'FAIL'} {name}: {what}: doc {stated:g}, now {measured:.6g} " \
           f"(tolerance {tolerance:g} + 0.1 %)"
    print(line)
    if not ok:
        failures.append(line)


def close_digits(name, what, measured, pattern):
    """A number quoted with its printed digits: the pattern has one group."""
    regex = re.sub(r"(\\ | )+", r"\\s+", pattern)
    m = re.search(regex, doc(name))
    if not m:
        sys.exit(f"check_docs: {name} no longer says /{pattern}/")
    text = m.group(1).replace("−", "-").replace(" ", "")
    close(name, what, measured, float(text), digits_tolerance(text))


def claim(name, what, ok):
    global checks
    checks += 1
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {what}")
    if not ok:
        failures.append(f"{name}: {what}")


def model(path):
    with open(path) as f:
        return json.load(f)


# ---- docs/tutorial.md: every sh block, top to bottom, in an empty folder -------------------
tut = folder("tutorial")
blocks = re.findall(r"^```(?:sh|bash)[ \t]*\n(.*?)^```", doc("docs/tutorial.md"), re.S | re.M)
script = os.path.join(work, "tutorial.sh")
with open(script, "w") as f:
    f.write("\n".join(blocks))
log = run(["sh", "-e", "-x", script], tut)
log_text = log.stdout + log.stderr
claim("docs/tutorial.md", f"its {len(blocks)} sh blocks run without an error", True)

# "With these short settings both commands warn that the networks stopped at --max-epochs":
# the warning now fires only when the training MSE was still falling: H = 24 at 20 epochs
# and the typical network at 3 are (H = 16 has reached a plateau by its 20th epoch).
claim("docs/tutorial.md", "the short sweep and train both warn 'under-trained'",
      "H = 24 stopped at --max-epochs 20 while its training MSE was still falling" in log_text
      and "training stopped at --max-epochs 3 while the training MSE was still falling"
      in log_text)

# refine with its default iteration budget from the tutorial's tuned model.
tuned = model(os.path.join(tut, "model.json"))
refined = json.loads(run(["sysid", "refine", "--model", "model.json", "data/pulses.csv",
                          "--json"], tut).stdout)
iterations = refined["diagnostics"]["iterations"]
close("docs/tutorial.md", "refine's default converges in about N iterations", iterations,
      quoted("docs/tutorial.md", r"its default, 50, converges in about (\d+)"), 2)
close_digits("docs/tutorial.md", "a3 after refine", refined["a3"],
             r"a data-sheet `a3 = 6` becomes ≈ ([\d.]+)")
close_digits("docs/tutorial.md", "a3 after the tutorial's 5 iterations",
             model(os.path.join(tut, "model_refined.json"))["a3"],
             r"≈ ([\d.]+) after the 5 iterations above")
close("docs/tutorial.md", "a3's move [%]", 100 * abs(refined["a3"] / 6 - 1),
      quoted("docs/tutorial.md", r"with every other parameter: a (\d+) % move"), 1)
claim("docs/tutorial.md", "refine gives no warning on the tutorial's chain",
      not refined["diagnostics"]["warnings"])

# sysid validate on the tutorial's tuned model: the fits the tutorial quotes.
val = json.loads(run(["sysid", "validate", "--model", "model.json", "--json",
                      "data/waveform_square.csv", "data/waveform_sine_0.016625_1.9.csv"],
                     tut).stdout)["recordings"]
close_digits("docs/tutorial.md", "validate: the square wave's velocity fit [%]",
             val[0]["outputs"][0]["fit_percent"], r"On the square wave the velocity fit is ([\d.]+) %")
close_digits("docs/tutorial.md", "validate: the square wave's position fit [%]",
             val[0]["outputs"][1]["fit_percent"], r"\(position ([\d.]+) %\)")
close_digits("docs/tutorial.md", "validate: the slowest sine's velocity fit [%]",
             val[1]["outputs"][0]["fit_percent"], r"on the slowest sine it is\s+(−[\d.]+) %")

# Chapter 8, your own stage: the gains tune-pi picks and the two plants' tracking errors.
gains = json.loads(run(["sysid", "tune-pi", "--model", "own.json", "--loop-rate", "10000",
                        "--json"], tut).stdout)["tuning"]
close_digits("docs/tutorial.md", "tune-pi's Kp [V/m]", gains["kp_v_per_m"], r"Here Kp = ([\d.]+)\s+V/m")
close_digits("docs/tutorial.md", "tune-pi's Ki [V/(m s)]", gains["ki_v_per_m_s"], r"and Ki = ([\d.]+) V/\(m s\)")
close_digits("docs/tutorial.md", "tau from the MAT file's x [ms]",
             1e3 * model(os.path.join(tut, "own.json"))["tau"], r"so τ\s+here is ([\d.]+) ms")
close_digits("docs/tutorial.md", "tau from the CSV's recorded v [ms]", 1e3 * tuned["tau"],
             r"against the ([\d.]+) ms of the CSV's recorded v")
def track_rms(plant, extra=()):
    out = json.loads(run(["sysid", "track", "--plant", plant, "--kp", "1937.4", "--ki", "39907",
                          "--freq", "0.5", "--ff", "none,analytic", "--json", *extra],
                         tut).stdout)
    return {r["ff"]: 1e3 * r["rms_error_m"] for r in out["schemes"]}
own, twin = track_rms("own.json"), track_rms("virtual", ("--model", "own.json"))
close_digits("docs/tutorial.md", "model plant, PI alone: RMS e [mm]", own["none"],
             r"With PI alone the model plant's RMS error is ([\d.]+) mm")
close_digits("docs/tutorial.md", "twin, PI alone: RMS e [mm]", twin["none"],
             r"against the twin's ([\d.]+) mm")
close_digits("docs/tutorial.md", "twin, PI + analytic: RMS e [mm]", twin["analytic"],
             r"while the twin keeps ([\d.]+) mm")
close("docs/tutorial.md", "model plant, PI + analytic: RMS e [nm]", 1e6 * own["analytic"],
      quoted("docs/tutorial.md", r"the model cancels itself \((\d+) nm\)"), 1)

# ---- docs/robustness.md ------------------------------------------------------------------
# "The tutorial's chain (identify with a3 = 6, tune-delay, refine) moves every parameter by
# A–B %": the moves of the six parameters from the tuned model to the refined one.
moves = [100 * abs(refined[k] / tuned[k] - 1) for k in ("a1p", "a1n", "a2p", "a2n", "a3", "tau")]
lo, hi = quoted("docs/robustness.md", r"moves every parameter by (\d+)–(\d+) %")
close("docs/robustness.md", "smallest parameter move of the tutorial's chain [%]", min(moves),
      lo, 1)
close("docs/robustness.md", "largest parameter move of the tutorial's chain [%]", max(moves),
      hi, 1)
# The refine warning example (tests/robustness/reports.sh's chain): a3 = 20 given.
rep = folder("reports")
v = os.path.join(src, "datasets", "virtual", "pulses.csv")
run(["sysid", "identify", "--a3", "6", v, "-o", "m.json"], rep)
run(["sysid", "tune-delay", "--model", "m.json", v, "-o", "m.json"], rep)
m20 = model(os.path.join(rep, "m.json"))
m20["a3"] = 20.0
with open(os.path.join(rep, "m20.json"), "w") as f:
    json.dump(m20, f)
err = run(["sysid", "refine", "--model", "m20.json", v, "--max-iterations", "3", "--json"],
          rep).stderr
m = re.search(r"a3 moved from its given value 20 to ([\d.]+) \((-?\d+) %, (\d+) standard errors "
              r"of ([\d.]+)\)", err)
claim("docs/robustness.md", "refine warns about a3 = 20", m is not None)
if m:
    for i, (what, pattern) in enumerate([
            ("a3 refined from 20", r"gives `a3 moved from its given value 20 to ([\d.]+)"),
            ("its move [%]", r"given value 20 to [\d.]+\s+\((-?\d+) %"),
            ("standard errors", r"(\d+) standard errors of [\d.]+\)"),
            ("the standard error", r"standard errors of ([\d.]+)\)")]):
        close_digits("docs/robustness.md", what, float(m.group(i + 1)), pattern)

# ---- docs/emps.md --------------------------------------------------------------------------
emps = folder("emps")
gtau = quoted("docs/emps.md", r"gtau = ([\d.]+) N/V")
est = "datasets/emps/emps_estimation.csv"


def trajectory(*flags):
    out = json.loads(run(["sysid", "identify", "--method", "trajectory", *flags, "--json", est],
                         emps).stdout)
    return out, gtau / out["a3"]


sym, M = trajectory("--offset", "--symmetric-viscous")
d = sym["diagnostics"]
for what, value, pattern in [
        ("M = gtau/a3 [kg]", M, r"\| M = gtau/a3 \| ([\d.]+) ±"),
        ("Fv [N s/m]", sym["a1p"] * M, r"\| Fv = a1 M \| ([\d.]+) N·s/m"),
        # With the offset, a2p = a2 + c0 and a2n = a2 - c0 (the model file's form).
        ("Fc [N]", (sym["a2p"] + sym["a2n"]) / 2 * M, r"\| Fc = a2 M \| ([\d.]+) N \|"),
        ("offset [N]", d["offset_mps2"] * M, r"\| offset = c0 M \| ([−\d.]+) N"),
        ("relative error [%]", 100 * d["relative_error"], r"relative error of u \| ([\d.]+) %"),
        ("moving samples", d["samples_used"], r"\|v\| >= 1 mm/s:\s+(\d+ \d+) moving samples")]:
    close_digits("docs/emps.md", "symmetric + offset: " + what, value, pattern)
sym100, M100 = trajectory("--offset", "--symmetric-viscous", "--cutoff", "100")
for what, value, pattern in [
        ("M [kg]", M100, r"With a 100 Hz cut-off: M = ([\d.]+) kg"),
        ("Fv [N s/m]", sym100["a1p"] * M100, r"100 Hz cut-off: M = [\d.]+ kg, Fv = ([\d.]+)"),
        ("Fc [N]", (sym100["a2p"] + sym100["a2n"]) / 2 * M100,
         r"100 Hz cut-off:.*?Fc = ([\d.]+) N")]:
    close_digits("docs/emps.md", "100 Hz: " + what, value, pattern)
split, Ms = trajectory()
ds = split["diagnostics"]
for what, value, pattern in [
        ("relative error [%]", 100 * ds["relative_error"], r"fits better — relative error ([\d.]+) %"),
        ("a3", split["a3"], r"%:\s+a3 = ([\d.]+) \(M ="),
        ("M [kg]", Ms, r"a3 = [\d.]+ \(M = ([\d.]+) kg\)"),
        ("a1p [1/s]", split["a1p"], r"a1p = ([\d.]+), a1n"),
        ("a1n [1/s]", split["a1n"], r"a1n = ([\d.]+) 1/s"),
        ("a2p [m/s^2]", split["a2p"], r"a2p = ([\d.]+), a2n"),
        ("a2n [m/s^2]", split["a2n"], r"a2n = ([\d.]+) m/s\^2")]:
    close_digits("docs/emps.md", "direction-split: " + what, value, pattern)
tuned_emps, Mt = trajectory("--tune-delay")
dt = tuned_emps["diagnostics"]
close_digits("docs/emps.md", "--tune-delay: tau [ms]", 1e3 * tuned_emps["tau"],
             r"`--tune-delay` picks tau ≈ ([\d.]+) ms")
close_digits("docs/emps.md", "--tune-delay: relative error [%]", 100 * dt["relative_error"],
             r"lowers the error only to\s+([\d.]+) %")
close_digits("docs/emps.md", "--tune-delay: M [kg]", Mt, r"while moving M to ([\d.]+) kg")

# ---- Python: the EMPS validation table, docs/python.md's tutorial, README's example --------
# The interpreter the package was built for: SYSID_PYTHON, else Debian's (docs/python.md: use
# /usr/bin/python3), else this one; the python3 running this script may be another (a pyenv
# one without NumPy).
have_python = False
for python in (os.environ.get("SYSID_PYTHON"), "/usr/bin/python3", sys.executable):
    if python and os.access(python, os.X_OK) and subprocess.run(
            [python, "-c", "import sysid"], env=env, capture_output=True).returncode == 0:
        have_python = True
        break
if not have_python:
    print("skip the Python checks: the sysid package is not importable here")
else:
    # docs/emps.md's validation table: its python block, run as written.
    emps_block = re.search(r"^```python\n(.*?)^```", doc("docs/emps.md"), re.S | re.M)
    claim("docs/emps.md", "the validation table has the command that makes it", emps_block
          is not None)
    if emps_block:
        with open(os.path.join(emps, "validation.py"), "w") as f:
            f.write(emps_block.group(1))
        out = run([python, "validation.py"], emps).stdout
        rows = dict(re.findall(r"^(direction-split|symmetric \+ offset)\s+(.*)$", out, re.M))
        table = doc("docs/emps.md")
        for label in ("direction-split", "symmetric + offset"):
            printed = rows.get(label, "").split()
            m = re.search(r"^\| " + re.escape(label) + r" \| ([\d.]+) % \| ([\d.]+) % \| "
                          r"([\d.]+) % \|", table, re.M)
            claim("docs/emps.md", f"validation row '{label}' printed and in the table",
                  bool(m) and len(printed) == 3)
            if m and len(printed) == 3:
                for col, what in enumerate(("estimation set", "validation, all moving",
                                            "validation, away from the pulses")):
                    close("docs/emps.md", f"{label}: {what} [%]", float(printed[col]),
                          float(m.group(col + 1)), digits_tolerance(m.group(col + 1)))
        close_digits("docs/emps.md", "samples away from the pulses",
                     float(re.search(r"away from the pulses: (\d+) samples", out).group(1)),
                     r"300 ms after any force pulse \((\d+ \d+) samples\)")
    # docs/python.md's tutorial and README's example, as written, in empty folders.
    for name in ("docs/python.md", "README.md"):
        block = re.search(r"^```python\n(.*?)^```", doc(name), re.S | re.M).group(1)
        where = folder("py_" + name.replace("/", "_"))
        with open(os.path.join(where, "example.py"), "w") as f:
            f.write(block)
        out = run([python, "example.py"], where).stdout
        claim(name, "the first python block runs as written", True)
        if name == "docs/python.md":
            said = re.search(r"print\(fit.termination, fit.message\)\s+# '([\w-]+)'",
                             doc(name)).group(1)
            lines = out.splitlines()
            # The termination line is the one printed just before the test MSE.
            at = next((i for i, l in enumerate(lines) if l.startswith("test MSE")), 0)
            claim(name, f"fit.termination is '{said}' as its comment says",
                  at >= 1 and lines[at - 1].split()[0] == said)

shutil.rmtree(work, ignore_errors=True)
print(f"check_docs: {checks} checks, {len(failures)} failed, "
      f"{time.monotonic() - started:.0f} s")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
