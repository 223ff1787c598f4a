#!/usr/bin/env bash
# Installs every Debian 12 package pogear builds, tests and benchmarks with. Idempotent.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  ninja-build                      # CI's generator (.ci/run): it schedules every object of the build on one graph
  libginac-dev libcln-dev          # symbolic derivation
  libeigen3-dev                    # numeric linear algebra, matrix exponential
  libfmt-dev libtomlplusplus-dev libcli11-dev
  libgtest-dev googletest
  gnuplot-nox                      # plots of simulations
  texlive-latex-base texlive-latex-recommended  # the tests compile the LaTeX reports with pdflatex
  libsundials-dev libboost-dev     # benchmark peers (bench/): CVODE, Boost.Odeint
  python3-scipy python3-numpy      # benchmark peer: SciPy's solve_ivp
  clang libclang-rt-14-dev         # fuzzing: libFuzzer, ASan and UBSan for clang (scripts/fuzz.sh)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
