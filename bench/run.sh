#!/usr/bin/env bash
# Builds and runs every benchmark (work-precision against CVODE, Boost.Odeint and SciPy; across the
# events of a shift; rigid vs elastic; effects on/off; generator cost; rigid sweeps), then writes
# CSVs, SVG plots and summary.md.
# Usage: bash bench/run.sh [--quick] [--out DIR] [--build DIR] [--no-build --bin DIR --pogear PATH]
#   --quick      a smoke test in well under a minute that checks the numbers (the ctest test)
#   --out DIR    results (default bench/results, bench/results-quick with --quick)
#   --build DIR  build directory of the standalone bench project (default build-bench)
#   --no-build   use binaries already built: --bin DIR holds them, --pogear PATH is the generator
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=0 out="" build="$root/build-bench" do_build=1 bin="" pogear=""
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --out) out=$2; shift ;;
    --build) build=$2; shift ;;
    --no-build) do_build=0 ;;
    --bin) bin=$2; shift ;;
    --pogear) pogear=$2; shift ;;
    *) echo "usage: $0 [--quick] [--out DIR] [--build DIR] [--no-build --bin DIR --pogear PATH]" >&2; exit 1 ;;
  esac
  shift
done
# No command substitution that may fail in an assignment: under `set -e` it would end the script
# without a word (bash 5.2).
if [ -z "$out" ]; then
  out="$root/bench/results"
  if [ $quick = 1 ]; then out="$out-quick"; fi
fi
[ $do_build = 1 ] || { [ -n "$bin" ] && [ -n "$pogear" ]; } ||
  { echo "error: --no-build needs --bin DIR and --pogear PATH" >&2; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)

if [ $do_build = 1 ]; then
  echo "== building the benchmarks in $build"
  cmake -S "$root/bench" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$out/cmake.log"
  grep -E '^-- bench:' "$out/cmake.log" || true
  # -j2: the machine is shared; the timings below run one at a time anyway.
  cmake --build "$build" -j2 >> "$out/cmake.log" 2>&1 || { tail -40 "$out/cmake.log"; exit 2; }
  bin=$build
  pogear=$build/pogear/pogear
fi

flags=(--out "$out" --check)
[ $quick = 1 ] && flags+=(--quick)
failed=()
run() {  # run NAME CMD...: a failing check or crash is reported and remembered, the rest still runs
  local name=$1
  shift
  echo "== $name"
  if ! "$@"; then
    failed+=("$name")
    echo "!! $name failed" >&2
  fi
}

# The machine and its load, for the record: timings are only comparable at low load.
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "mode: $([ $quick = 1 ] && echo quick || echo full)"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "cpus: $(nproc)"
  echo "compiler: $(${CXX:-c++} --version | head -1)"
  echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out/machine.txt"
cat "$out/machine.txt"
load=$(cut -d' ' -f1 /proc/loadavg)
awk -v l="$load" 'BEGIN { exit !(l > 1.2) }' && echo "note: load average $load > 1.2: timings will be noisy"

# 1, 2. Work-precision and rigid vs elastic (pogear's methods also write the problems for SciPy).
run "pogear methods" "$bin/bench_wp_pogear" "${flags[@]}"
if [ -x "$bin/bench_wp_cvode" ]; then run "CVODE" "$bin/bench_wp_cvode" "${flags[@]}"
else echo "note: CVODE skipped (not built: install libsundials-dev)"; fi
if [ -x "$bin/bench_wp_odeint" ]; then run "Boost.Odeint" "$bin/bench_wp_odeint" "${flags[@]}"
else echo "note: Boost.Odeint skipped (not built: install libboost-dev)"; fi
python=""
for p in python3 /usr/bin/python3; do  # a pyenv python3 may shadow the Debian one that has SciPy
  if command -v "$p" > /dev/null && "$p" -c 'import scipy, numpy, tomllib' 2> /dev/null; then python=$p; break; fi
done
if [ -n "$python" ]; then
  run "SciPy" "$python" "$root/bench/wp_scipy.py" --pogear "$pogear" --problems "$out/problems" --out "$out" \
    --check $([ $quick = 1 ] && echo --quick)
else
  echo "note: SciPy skipped (no python3 with scipy, numpy and tomllib: install python3-scipy)"
  rm -f "$out/wp_scipy.csv"
fi
{
  head -1 "$out/wp_pogear.csv"
  for f in "$out"/wp_pogear.csv "$out"/wp_cvode.csv "$out"/wp_odeint.csv "$out"/wp_scipy.csv; do
    [ -f "$f" ] && tail -n +2 "$f"
  done
} > "$out/wp.csv"

# Across events: the Simpson upshift with pogear's hybrid engine, CVODE's root finding and SciPy's
# solve_ivp events, against a long-double reference (the C++ harness writes the problem for SciPy).
run "events" "$bin/bench_events" "${flags[@]}"
if [ -n "$python" ] && [ -f "$out/events_problem/simpson_1_2_upshift.json" ]; then
  run "SciPy events" "$python" "$root/bench/events_scipy.py" --problem "$out/events_problem" --out "$out" \
    --check $([ $quick = 1 ] && echo --quick)
else
  rm -f "$out/events_scipy.csv"
fi
{
  head -1 "$out/events_cpp.csv"
  for f in "$out"/events_cpp.csv "$out"/events_scipy.csv; do
    [ -f "$f" ] && tail -n +2 "$f"
  done
} > "$out/events.csv"

# Writing the samples: formatting and the file system, apart.
run "CSV cost" "$bin/bench_csv_cost" "${flags[@]}"

# 3. Effects on and off; the variant scenes are kept next to the results for reference.
run "effects" "$bin/bench_effects" "${flags[@]}"
mkdir -p "$out/scenes"
cp "$bin"/variants/*.toml "$bin"/variants/*.ops.txt "$out/scenes/" 2> /dev/null || true

# 4. The generator's own cost, as whole processes: the paper models, then chains of k stages.
echo "== generator cost"
gen="$out/generator.csv"
echo "what,model,k,bodies,runs,median_s,min_s,max_s,status" > "$gen"
mkdir -p "$out/chains" "$out/generated"
timeout=$([ $quick = 1 ] && echo 20 || echo 60)
# A chain's run is capped tighter, so the sweep to k = 40 stays within minutes: past the cap, larger
# chains of that command are recorded as skipped.
chain_timeout=$([ $quick = 1 ] && echo 20 || echo 30)
min_total=$([ $quick = 1 ] && echo 0.05 || echo 0.5)
time_proc() {  # time_proc LABEL CMD...   (TIMEOUT in the environment overrides the cap)
  local label=$1
  shift
  "$bin/bench_proc_time" --csv "$gen" --label "$label" --min-total "$min_total" --max-runs 20 \
    --timeout "${TIMEOUT:-$timeout}" -- "$@"
}
for m in paper_one_stage paper_two_stage; do
  bodies=$(grep -c '^\[\[body\]\]' "$root/models/$m.toml")
  time_proc "derive,$m,,$bodies" "$pogear" derive "$root/models/$m.toml" --format json || failed+=("derive $m")
  time_proc "generate,$m,,$bodies" "$pogear" generate "$root/models/scenes/$m.toml" -o "$out/generated" \
    || failed+=("generate $m")
done
ks=$([ $quick = 1 ] && echo "1 2 3 4" || echo "$(seq -s ' ' 1 20) 25 30 35 40")
declare -A stop=([derive]="" [generate]="")  # derive and generate stop on their own
for k in $ks; do
  model="$out/chains/chain_$k.toml"
  bash "$root/scripts/make_chain.sh" "$k" > "$model"
  bash "$root/scripts/make_chain.sh" "$k" --scene "$model" > "$out/chains/chain_${k}_scene.toml"
  for what in derive generate; do
    if [ -n "${stop[$what]}" ]; then  # past the time limit: larger chains are not run
      echo "$what,chain,$k,$((3 * k + 1)),0,,,,skipped (${stop[$what]})" >> "$gen"
      continue
    fi
    if [ $what = derive ]; then
      TIMEOUT=$chain_timeout time_proc "derive,chain,$k,$((3 * k + 1))" "$pogear" derive "$model" --format json || true
    else
      TIMEOUT=$chain_timeout time_proc "generate,chain,$k,$((3 * k + 1))" "$pogear" generate \
        "$out/chains/chain_${k}_scene.toml" -o "$out/generated" || true
    fi
    status=$(tail -1 "$gen" | cut -d, -f9)
    case "$status" in
      ok) ;;
      timeout) stop[$what]="$what of k = $k took more than $chain_timeout s" ;;
      "failed (exit 2)")  # an input error: the generator refuses the model (e.g. a size limit)
        msg=$({ "$pogear" derive "$model" --format json 2>&1 > /dev/null || true; } | head -1 |
          sed 's/.*error: //; s/,/ /g; s/;/:/g')
        sed -i '$ s/failed (exit 2)$/refused: '"${msg//\//\/}"'/' "$gen"
        stop[derive]="k = $k refused"; stop[generate]="k = $k refused" ;;
      *) failed+=("$what chain_$k: $status"); stop[$what]="$what of k = $k failed" ;;
    esac
  done
done

# 5. Rigid sweeps.
run "rigid sweep" "$bin/bench_sweep" "${flags[@]}"

echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/machine.txt"
run "report" bash "$root/bench/report.sh" "$out"
if [ ${#failed[@]} -gt 0 ]; then
  printf 'FAILED: %s\n' "${failed[@]}" >&2
  exit 1
fi
echo "all benchmarks done: $out"
