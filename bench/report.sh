#!/usr/bin/env bash
# Turns the CSVs of bench/run.sh into SVG plots (gnuplot) and OUT/summary.md: work-precision per
# scene and model, generator time vs chain length, the fastest configurations at given errors, and
# the tables of steps, rigid vs elastic, effects, sweeps and the generator.
# Usage: bash bench/report.sh OUT
set -euo pipefail
out=${1:?usage: report.sh OUT}
cd "$out"
mkdir -p plot

# ---- work-precision data: one file per scene, model and method, points ordered by the knob -------
# Only successful runs with a finite error; an error below 1e-16 is drawn at 1e-16 (log axis).
rm -f plot/*.dat
awk -F, 'NR > 1 && $7 == "ok" && $10 != "nan" && $11 != "nan" {
  e = $10 + 0; if (e < 1e-16) e = 1e-16
  f = "plot/" $1 "." $2 "." $4 ".dat"
  print $11, e, $6 >> f
}' wp.csv

# Method order, labels and styles: pogear solid, CVODE dashed, odeint dotted, SciPy dash-dotted.
styles() {
  cat <<'EOF'
exact|pogear exact|lc rgb "#000000" pt 7 ps 1.6
exact_outputs|pogear exact, outputs|lc rgb "#555555" pt 5 ps 1.2
exact_csv|pogear exact + CSV|lc rgb "#999999" pt 9 ps 1.4
rk4|pogear rk4|lc rgb "#1f77b4" pt 4 dt 1
dopri5|pogear dopri5|lc rgb "#d62728" pt 6 dt 1
implicit|pogear implicit (TR-BDF2)|lc rgb "#2ca02c" pt 8 dt 1
cvode_bdf|CVODE BDF|lc rgb "#9467bd" pt 10 dt 2
cvode_adams|CVODE Adams|lc rgb "#8c564b" pt 12 dt 2
odeint_dopri5|odeint dopri5|lc rgb "#e377c2" pt 1 dt 3
odeint_rosenbrock4|odeint rosenbrock4|lc rgb "#7f7f7f" pt 2 dt 3
scipy_RK45|SciPy RK45|lc rgb "#bcbd22" pt 3 dt 4
scipy_DOP853|SciPy DOP853|lc rgb "#17becf" pt 13 dt 4
scipy_Radau|SciPy Radau|lc rgb "#ff7f0e" pt 11 dt 4
scipy_BDF|SciPy BDF|lc rgb "#1a55ff" pt 14 dt 4
scipy_LSODA|SciPy LSODA|lc rgb "#aa3377" pt 15 dt 4
EOF
}

if command -v gnuplot > /dev/null; then
  for f in $(ls plot/*.dat | sed -E 's#plot/([^.]*)\.([^.]*)\..*#\1.\2#' | sort -u); do
    scene=${f%.*} model=${f#*.}
    plots=""
    while IFS='|' read -r m label style; do
      dat="plot/$scene.$model.$m.dat"
      [ -f "$dat" ] || continue
      [ -n "$plots" ] && plots+=", "
      plots+="'$dat' using 1:2 with linespoints $style lw 1.5 title '$label'"
    done < <(styles)
    gnuplot <<EOF
set terminal svg size 900,560 font "Helvetica,12" background rgb "white"
set output "wp_${scene}_${model}.svg"
set title "Work-precision: ${scene//_/ }, ${model} model"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "wall time per simulated second [s] (median)"
set ylabel "max relative error of the sampled trajectory"
set key outside right top spacing 1.1
set grid
plot $plots
EOF
  done
  # Generator cost vs chain length.
  awk -F, 'NR > 1 && $2 == "chain" && $9 == "ok" { print $3, $4, $6 > ("plot/gen_" $1 ".dat") }' generator.csv
  if [ -f plot/gen_derive.dat ]; then
    # Where the generator refuses the model (a size limit), a line says so.
    refused=$(awk -F, '$2 == "chain" && $9 ~ /^refused/ { print $3; exit }' generator.csv)
    marker=""
    [ -n "$refused" ] && marker="set arrow from first $refused, graph 0 to first $refused, graph 1 nohead dt 3 lc rgb '#cc0000'
set label 'k >= $refused: refused by pogear' at first $refused, graph 0.08 right offset -0.5,0 tc rgb '#cc0000'
set xrange [0:$((refused + 1))]"
    gnuplot <<EOF
set terminal svg size 800,500 font "Helvetica,12" background rgb "white"
set output "generator_vs_k.svg"
set xrange [0:*]
set title "Generator cost: chains of k planetary stages (3k+1 bodies, 2k meshes, k+1 dof)"
set logscale y
set format y "10^{%L}"
set xlabel "stages k"
set ylabel "wall time of the whole process [s] (median)"
set key left top
set grid
set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc rgb "#999999"
set label "1 s" at graph 0.02, first 1.3 tc rgb "#666666"
$marker
plot 'plot/gen_derive.dat' using 1:3 with linespoints pt 7 lw 2 title "pogear derive --format json", \
     'plot/gen_generate.dat' using 1:3 with linespoints pt 5 lw 2 title 'pogear generate (scene with compare\_rigid)'
EOF
  fi
else
  echo "note: gnuplot not found: no plots (install gnuplot-nox)"
fi

# ---- summary.md ---------------------------------------------------------------------------------
{
  echo "# Benchmark summary"
  echo
  echo '```'
  cat machine.txt
  echo '```'
  echo
  echo "Times are medians of batches (each batch repeats a run until it lasts >= 50 ms; 5 batches; 2 ms"
  echo "and 3 in --quick), as wall time per simulated second. Errors: the largest deviation from the exact"
  echo "reference over the 1 ms samples, each state relative to its largest magnitude."
  echo
  echo "## Fastest configuration per family at a required error"
  echo
  for target in 1e-6 1e-8 1e-9; do
    echo "### max relative error <= $target"
    echo
    echo "| scene | model | pogear | CVODE | odeint | SciPy | CVODE / pogear | odeint / pogear | SciPy / pogear |"
    echo "|---|---|---|---|---|---|---|---|---|"
    awk -F, -v target="$target" '
      NR > 1 && $7 == "ok" && $10 != "nan" && $10 + 0 <= target + 0 && $11 != "nan" {
        key = $1 "|" $2 "|" $3
        if (!(key in best) || $11 + 0 < best[key]) {
          best[key] = $11 + 0
          what[key] = $4 ($5 == "" ? "" : " " $5 "=" $6)
        }
        sm[$1 "|" $2] = 1
      }
      END {
        n = split("pogear cvode odeint scipy", fam, " ")
        for (k in sm) {
          split(k, a, "|")
          line = "| " a[1] " | " a[2] " |"
          for (i = 1; i <= n; ++i) {
            key = k "|" fam[i]
            line = line ((key in best) ? sprintf(" %s: %.3g |", what[key], best[key]) : " none |")
          }
          p = k "|pogear"
          for (i = 2; i <= n; ++i) {
            key = k "|" fam[i]
            line = line (((key in best) && (p in best)) ? sprintf(" %.0f |", best[key] / best[p]) : " |")
          }
          print line
        }
      }' wp.csv | sort
    echo
  done

  if [ -f events.csv ]; then
    echo "## Across events: the Simpson 1-2 upshift (elastic, 8 events)"
    echo
    echo "Errors against a long-double reference: the states at the 1 ms samples (as above) and the event"
    echo "times (seconds; inf when a run's events differ from the reference's)."
    echo
    echo "### Fastest per family with state error <= 1e-8 and event-time error <= 1e-9 s"
    echo
    echo "| family | fastest | s per simulated s | state error | event error | / pogear |"
    echo "|---|---|---|---|---|---|"
    awk -F, 'NR > 1 && $7 == "ok" && $10 != "nan" && $10 + 0 <= 1e-8 && $11 != "inf" && $11 + 0 <= 1e-9 {
        if (!($3 in best) || $12 + 0 < best[$3]) { best[$3] = $12 + 0; what[$3] = $4 ($5 == "" ? "" : " " $5 "=" $6); se[$3] = $10; ee[$3] = $11 }
      }
      END {
        n = split("pogear cvode scipy", fam, " ")
        for (i = 1; i <= n; ++i) {
          f = fam[i]
          if (f in best) printf "| %s | %s | %.3g | %s | %s | %s |\n", f, what[f], best[f], se[f], ee[f], ("pogear" in best) ? sprintf("%.0f", best[f] / best["pogear"]) : ""
          else printf "| %s | none reaches it | | | | |\n", f
        }
      }' events.csv
    echo
    echo "### Every run"
    echo
    echo "| method | knob | value | status | steps | events | state error | event error [s] | s per simulated s | note |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %.3g | %s |\n", $4, $5, $6, $7, $8, $9, $10, $11, $12, $17 }' events.csv
    echo
  fi

  echo "## Exact stepping: cost of one step"
  echo
  echo "| scene | model | states | what | ns per step (median) | min | max |"
  echo "|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %.3g | %.3g | %.3g |\n", $1, $2, $3, $4, $5, $6, $7 }' exact_step.csv
  echo
  echo "## pogear exact with and without output formatting (s per simulated s)"
  echo
  echo "| scene | model | states only | outputs computed | outputs + CSV | CSV / states only |"
  echo "|---|---|---|---|---|---|"
  awk -F, 'NR > 1 && $3 == "pogear" && $4 ~ /^exact/ { t[$1 "|" $2 "|" $4] = $11; k[$1 "|" $2] = 1 }
    END { for (x in k) { split(x, a, "|"); e = t[x "|exact"]; c = t[x "|exact_csv"]
      printf "| %s | %s | %.3g | %.3g | %.3g | %.0f |\n", a[1], a[2], e, t[x "|exact_outputs"], c, c / e } }' wp.csv | sort
  echo
  if [ -f csv_cost.csv ]; then
    echo "## Writing the CSV, apart: one file of every sample's outputs (CsvWriter, as the generated main)"
    echo
    echo "memory: /dev/shm, so formatting and copying only; disk: the results directory's file system."
    echo
    echo "| scene | model | where | rows | numbers | bytes | s per file (median) | min | max | ns per number |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %.3g | %.3g | %.3g | %.3g |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10 }' \
      csv_cost.csv
    echo
  fi
  echo "## Rigid vs elastic"
  echo
  echo "| scene | method | elastic s/s | rigid s/s | speedup | elastic error | rigid error (own reference) |"
  echo "|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %.3g | %.3g | %.1f | %.2g | %.2g |\n", $1, $2, $3, $4, $5, $6, $7 }' \
    rigid_vs_elastic_time.csv
  echo
  echo "Rigid model against the elastic one (both exact), relative to each elastic output's largest magnitude:"
  echo
  echo "| scene | outputs | transient (t <= 0.3 s) | after |"
  echo "|---|---|---|---|"
  awk -F, 'NR > 1 && $2 ~ /^all / { v[$1 "|" $2 "|" $3] = $4; k[$1 "|" $2] = 1 }
    END { for (x in k) { split(x, a, "|"); printf "| %s | %s | %.2g | %.2g |\n", a[1], a[2], v[x "|transient"], v[x "|after"] } }' \
    rigid_vs_elastic_error.csv | sort
  echo
  echo "## Effects on and off"
  echo
  echo "| scene | variant | system | states | rhs ops | outputs ops | rhs ns | outputs ns | rk4 s/s | exact s/s | dopri5 s/s (steps) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %.3g | %.3g | %.3g | %.3g | %.3g (%s) |\n",
    $1, $2, $4, $5, $7, $10, $11, $12, $13, $15, $17, $18 }' effects.csv
  echo
  echo "## Generator (whole processes)"
  echo
  echo "| what | model | k | bodies | median s | min | max | runs | status |"
  echo "|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $6, $7, $8, $5, $9 }' \
    generator.csv
  awk -F, 'NR > 1 && $2 == "chain" && $9 == "ok" && $6 + 0 > 1 && !($1 in first) { first[$1] = $3 }
    END { for (w in first) printf "\n%s takes more than 1 s from k = %s on.\n", w, first[w] }' generator.csv
  echo
  echo "## Rigid sweeps (2 s horizon, 1 ms samples, exact)"
  echo
  echo "| scene | mode | threads | runs/s (median) | min | max |"
  echo "|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %s | %.3g | %.3g | %.3g |\n", $1, $5, $6, $7, $8, $9 }' sweep.csv
} > summary.md
echo "wrote $out/summary.md and $(ls ./*.svg 2> /dev/null | wc -l) plots"
