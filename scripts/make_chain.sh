#!/usr/bin/env bash
# Writes a synthetic model of K planetary stages in series (a pogear model file, TOML) to stdout,
# for measuring how the generator's cost grows with the size of the gear.
# Usage: scripts/make_chain.sh K [--scene MODEL_PATH]   (--scene writes a scene for that model instead)
#
# Stage i has a sun, a planet p<i> on carrier c<i> and a ring r<i>. The stages are coupled by
# sharing a body: the sun of stage i+1 is a wheel on carrier c<i> (a carrier may carry wheels), so
# the gear has 3K+1 bodies, 2K meshes and K+1 degrees of freedom (the first sun and the rings).
# Radii vary from stage to stage so that no two stages are alike, and satisfy the geometry
# relations d<i> = r_p<i> + r_s<i> (planet axis distance), r_r<i> = 2 r_p<i> + r_s<i> (ring).
set -euo pipefail

usage() { echo "usage: $0 K [--scene MODEL_PATH]" >&2; exit 1; }
[ $# -ge 1 ] || usage
k=$1
[[ $k =~ ^[1-9][0-9]*$ ]] || usage

if [ $# -ge 2 ]; then
  [ "$1" ] && [ "$2" = "--scene" ] && [ $# -eq 3 ] || usage
  # The scene: every effect, 100 N m on the first sun from rest, 1 s, as in the paper's scenes.
  cat <<EOF
# Scene for the synthetic ${k}-stage chain (scripts/make_chain.sh ${k} --scene).
name = "chain_${k}"
model = "$3"
effects = ["mesh_compliance", "mesh_damping", "bearing_friction", "mesh_forces"]
compare_rigid = true

[inputs]
tau_s1 = { constant = "100*Nm" }

[simulation]
horizon = "1*s"
sample = "1*ms"
EOF
  exit 0
fi

awk -v k="$k" 'BEGIN {
  printf "# Synthetic chain of %d planetary stages (scripts/make_chain.sh %d): the carrier of stage i\n", k, k
  printf "# carries the sun wheel of stage i+1. %d bodies, %d meshes, %d degrees of freedom.\n", 3 * k + 1, 2 * k, k + 1
  printf "name = \"chain_%d\"\n", k
  # The first sun and every ring parametrize the rigid motions (the planets and carriers follow);
  # naming them avoids a search through the valid sets, which grows combinatorially with k.
  keep = "\"s1\""
  for (i = 1; i <= k; ++i) keep = keep sprintf(", \"r%d\"", i)
  printf "keep = [%s]\n\n", keep

  printf "[[body]]\nname = \"s1\"\naxis = \"central\"\n\n"
  for (i = 1; i <= k; ++i) {
    printf "[[body]]\nname = \"c%d\"\naxis = \"central\"\n", i
    if (i < k) printf "wheels = [ { name = \"s%d\", radius = \"r_s%d\" } ]\n", i + 1, i + 1
    # the last carrier has no teeth: no wheels key
    printf "\n[[body]]\nname = \"p%d\"\naxis = { carrier = \"c%d\", distance = \"d%d\" }\n\n", i, i, i
    printf "[[body]]\nname = \"r%d\"\naxis = \"central\"\n", i
    printf "wheels = [ { name = \"r%d\", radius = \"r_r%d\", internal = true } ]\n\n", i, i
  }
  for (i = 1; i <= k; ++i) {
    printf "[[mesh]]\nname = \"sp%d\"\nfirst = \"s%d\"\nsecond = \"p%d\"\n\n", i, i, i
    printf "[[mesh]]\nname = \"pr%d\"\nfirst = \"p%d\"\nsecond = \"r%d\"\n\n", i, i, i
  }

  printf "[parameters]\n"
  for (i = 1; i <= k; ++i) {
    # Radii in mm: suns 30..39, planets 15..24, so every stage has its own ratio.
    rs = 30 + (i * 7) % 10; rp = 15 + (i * 3) % 10
    printf "r_s%d = \"%d*mm\"\nr_p%d = \"%d*mm\"\n", i, rs, i, rp
    printf "d%d = \"%d*mm\"\n", i, rp + rs                 # d = r_p + r_s
    printf "r_r%d = \"%d*mm\"\n", i, 2 * rp + rs           # r_r = 2 r_p + r_s
    # Inertias grow along the chain (slower stages are bigger); one friction and one mesh law.
    printf "J_c%d = \"%g*kg*meters^2\"\nJ_p%d = \"%g*kg*meters^2\"\nJ_r%d = \"%g*kg*meters^2\"\n", \
      i, 0.01 * i, i, 0.002 + 0.0005 * i, i, 0.005 * i
    printf "b_c%d = \"0.08*Nm/rpm\"\nb_p%d = \"b_c%d\"\nb_r%d = \"b_c%d\"\n", i, i, i, i, i
    printf "K_sp%d = \"1000*Newton/mm\"\nK_pr%d = \"K_sp%d\"\n", i, i, i
    printf "b_sp%d = \"0.4*Newton*s/cm\"\nb_pr%d = \"b_sp%d\"\n", i, i, i
  }
  printf "J_s1 = \"0.0062509*kg*meters^2\"\nb_s1 = \"0.08*Nm/rpm\"\n"
}'
