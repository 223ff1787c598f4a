#!/usr/bin/env bash
# Fuzzes pogear's readers of users' files (fuzz/: model files, scene files, parameter expressions)
# under ASan and UBSan, each target for SECONDS (default 45). Exits non-zero on any finding.
# Usage: scripts/fuzz.sh [SECONDS]    (POGEAR_FUZZ_BUILD_DIR=DIR to build elsewhere)
# Builds with clang in build-fuzz/; the growing corpus stays in build-fuzz/corpus/<target>, and a
# crashing, leaking, hanging or memory-hungry input is saved in build-fuzz/findings/<target>/ (copy
# it to fuzz/regressions/<target>/ once fixed, so that ctest replays it for ever).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-45}
[[ $seconds =~ ^[1-9][0-9]*$ ]] || { echo "usage: $0 [SECONDS]" >&2; exit 1; }
build=${POGEAR_FUZZ_BUILD_DIR:-build-fuzz}  # another directory for a second checkout's runs
targets=(model scene quantity)

# A build directory already configured with POGEAR_FUZZ (CI's build-asan, which also holds the
# sanitized test suite) is used as it is; any other is configured for the fuzzers alone.
if ! grep -qx 'POGEAR_FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
  CC=clang CXX=clang++ cmake -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPOGEAR_FUZZ=ON -DPOGEAR_BUILD_TESTS=OFF >/dev/null
fi
cmake --build "$build" -j2 --target "${targets[@]/#/fuzz_}"

# Seeds from the project's own files, taken at run time so that they follow the models.
for t in "${targets[@]}"; do mkdir -p "$build/corpus/$t" "$build/findings/$t"; done
cp models/*.toml "$build/corpus/model/"
for f in models/scenes/*.toml; do  # the scene target supplies the model line itself
  grep -v '^model *=' "$f" >"$build/corpus/scene/$(basename "$f")"
done
# Every quoted parameter value, one expression per file.
grep -ho '= *"[^"]*"' models/*.toml models/scenes/*.toml | sed 's/^= *"//; s/"$//' | sort -u |
  while IFS= read -r expr; do
    printf '%s' "$expr" >"$build/corpus/quantity/$(printf '%s' "$expr" | md5sum | cut -c1-16)"
  done

# ASan keeps every distinct allocation stack for ever, and GiNaC's term order (which follows the
# serial numbers of symbols) makes new stacks with every model: with 30-frame stacks and a 256 MB
# quarantine a run reached the 2 GB limit in about 10 minutes; with these it stays near 190 MB.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:malloc_context_size=2:quarantine_size_mb=64
export LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
summary=()
for t in "${targets[@]}"; do
  log="$build/fuzz_$t.log"
  echo "== fuzz_$t: $seconds s"
  # The first corpus directory receives the new inputs; the others are read-only seeds.
  seeds=()
  for d in "fuzz/corpus/$t" "fuzz/regressions/$t"; do [ -d "$d" ] && seeds+=("$d"); done
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GB is an out-of-memory finding.
  if ! "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -dict="fuzz/$t.dict" -artifact_prefix="$build/findings/$t/" "$build/corpus/$t" "${seeds[@]}" \
      </dev/null >"$log" 2>&1; then
    status=1
  fi
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  summary+=("fuzz_$t: ${seconds} s, ${execs:-?} executions, corpus $(ls "$build/corpus/$t" | wc -l) inputs")
  if grep -qE '^(==[0-9]+==ERROR|SUMMARY: |.*ERROR: libFuzzer)' "$log"; then
    status=1
    echo "fuzz_$t: FINDING (see $log and $build/findings/$t/):"
    grep -E '^(==[0-9]+==ERROR|SUMMARY: |.*ERROR: libFuzzer|artifact_prefix|Test unit written)' "$log" | head -20
  fi
done
printf '%s\n' "${summary[@]}"
exit $status
