#!/usr/bin/env bash
# Time to first result: the first `pogear simulate` of the paper scenes on an empty cache, against
# the compile of a minimal Eigen program (a 10x10 LU solve) on the same machine, in the same run.
# Usage: bash bench/first_result.sh [POGEAR] [RUNS]   (default build/pogear, 3 runs; the minimum counts)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
pogear=${1:-$root/build/pogear}
runs=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/eigen_min.cpp" <<'CPP'
#include <Eigen/Dense>
#include <cstdio>
int main() {
  Eigen::Matrix<double, 10, 10> A = Eigen::Matrix<double, 10, 10>::Random();
  Eigen::Matrix<double, 10, 1> b = Eigen::Matrix<double, 10, 1>::Ones();
  Eigen::Matrix<double, 10, 1> x = A.partialPivLu().solve(b);
  std::printf("%g\n", x.sum());
}
CPP

# The least wall time of `runs` runs of a command, in seconds; `prepare` runs before each, untimed.
best() {
  local prepare=$1
  shift
  local min=""
  for _ in $(seq "$runs"); do
    eval "$prepare"
    local start end t
    start=$(date +%s.%N)
    "$@" > /dev/null
    end=$(date +%s.%N)
    t=$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')
    if [ -z "$min" ] || awk -v t="$t" -v m="$min" 'BEGIN { exit !(t < m) }'; then min=$t; fi
  done
  printf '%.2f' "$min"
}

eigen=$(best ":" g++ -std=c++20 -O2 -DNDEBUG -I/usr/include/eigen3 "$work/eigen_min.cpp" -o "$work/eigen_min")
echo "minimal Eigen program (10x10 LU), g++ -O2: $eigen s"
for scene in paper_one_stage paper_two_stage; do
  t=$(best "rm -rf '$work/cache' '$work/out'" env POGEAR_CACHE_DIR="$work/cache" "$pogear" simulate \
        "$root/models/scenes/$scene.toml" -o "$work/out")
  cached=$(best ":" env POGEAR_CACHE_DIR="$work/cache" "$pogear" simulate "$root/models/scenes/$scene.toml" -o "$work/out")
  echo "$scene: first pogear simulate $t s ($(awk -v t="$t" -v e="$eigen" 'BEGIN { printf "%.2f", t / e }')x the Eigen program), cached $cached s"
done
