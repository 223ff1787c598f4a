#!/usr/bin/env bash
# Draws docs/scene-format/start.svg: the paper's one-stage scene started as given (at rest, meshes
# unloaded) and with start = "rigid", the ring-planet mesh force of each elastic run against the
# rigid model's. Usage: scripts/start_figure.sh [POGEAR] (default build/pogear).
set -euo pipefail
cd "$(dirname "$0")/.."
pogear=${1:-build/pogear}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=models/scenes/paper_one_stage.toml
model=$(realpath models/paper_one_stage.toml)
for start in given rigid; do
  sed -e "s|^name = .*|name = \"start_$start\"|" -e "s|^model = .*|model = \"$model\"|" \
      -e "s|^horizon = .*|horizon = \"0.1*s\"|" -e "s|^sample = .*|sample = \"0.1*ms\"|" \
      -e "s|^omega_c = .*|omega_c = \"0*rpm\"\nstart = \"$start\"|" "$scene" > "$work/start_$start.toml"
  "$pogear" simulate "$work/start_$start.toml" -o "$work" --interpreted > /dev/null
done
column=$(head -1 "$work/start_given.csv" | tr ',' '\n' | grep -n '^F_pr ' | cut -d: -f1)
gnuplot > docs/scene-format/start.svg <<GNUPLOT
set terminal svg size 900,500 dynamic enhanced font 'Helvetica,13' background rgb 'white'
set datafile separator ','
set title 'One-stage gear of the paper, 100 N m on the carrier from rest'
set xlabel 't [s]'
set ylabel 'F_{pr} [N]'
set grid
set key inside right bottom box opaque
plot '$work/start_given.csv' using 1:$column every ::1 with lines lw 2 lc rgb '#1f77b4' title 'start = "given" (elastic)', \
     '$work/start_rigid.csv' using 1:$column every ::1 with lines lw 2 lc rgb '#2ca02c' title 'start = "rigid" (elastic)', \
     '$work/start_given.rigid.csv' using 1:$column every ::1 with lines dt 2 lw 2 lc rgb '#d62728' title 'rigid model'
GNUPLOT
echo "wrote docs/scene-format/start.svg"
