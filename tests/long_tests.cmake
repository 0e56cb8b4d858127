# Read by CTest after the discovered Catch2 tests (TEST_INCLUDE_FILES in tests/CMakeLists.txt):
# the label "long" on the few module tests that take over 8 s in Release and whose paths other,
# shorter tests already run. CI's sanitizer pass leaves them out (scripts/test.sh --sanitize;
# docs/testing.md, "CI budget"); the Release pass runs them. A renamed test fails here loudly.
set(_long_tests
  # 32 s: the MAT writer and reader are the io tests' and the container fuzzers' subject
  "pipeline:generate --format mat writes the CSV folder's recordings as MAT files, and the pipeline identifies the same model from them"
  # 14 s: the same, through --var/--rate/--scale
  "pipeline:sysid pipeline maps every MAT recording of its folder with --var/--rate/--scale"
  # 11 s: CVODE against a tiny-step RK4, arithmetic only
  "hysteresis:bouc-wen: CVODE against a tiny-step RK4 for held, linear and band-limited input"
  # 8 s: generate byte for byte; stage: runs the same generators on shorter sets
  "stage:regression: sysid generate reproduces the bundled datasets byte for byte")
foreach(_name IN LISTS _long_tests)
  string(REGEX REPLACE ":.*" "" _module "${_name}")
  set_tests_properties("${_name}" PROPERTIES LABELS "${_module};long")
endforeach()
