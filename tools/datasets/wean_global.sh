#!/usr/bin/env bash
# Global localization on the CMU 16-831 Wean Hall logs (no reference, unknown
# start): converts wean.dat, imports robotdata1-5, runs slamer-localizer
# --global (lfm, every beam) and prints after how many scans and seconds each
# run settles and, with several seeds, from which scan the seeds' runs agree
# within 0.5 m, or which of them do (slamer-settle). Run from the repo root after building.
#   tools/datasets/wean_global.sh [OUT_DIR]
#   environment: PARTICLES (5000), SEEDS ("1"), DATASETS (folder of the logs)
set -euo pipefail
out=${1:-wean_output}
particles=${PARTICLES:-5000}
seeds=${SEEDS:-1}
data=${DATASETS:-../shared/datasets/cmu_wean_16831}
if [ ! -d "$data" ]; then
  echo "wean_global: $data is absent (set DATASETS)" >&2
  exit 1
fi
mkdir -p "$out"
# Each step's log goes beside its output; a failing step says which file to read.
step() {
  local log=$1
  shift
  "$@" 2>"$log" || { echo "wean_global: $1 failed, see $log" >&2; exit 1; }
}
step "$out/map.stderr" build/bin/slamer-mapgen --wean "$data/wean.dat.gz" "$out/map"
sed -E "s/^  particles: [0-9]+/  particles: $particles/" config/localizer.yaml > "$out/localizer.yaml"
for k in 1 2 3 4 5; do
  step "$out/log$k.stderr" build/bin/slamer-carmen2lcm "$data/robotdata$k.log.gz" "$out/log$k.lcm" --format cmu
  for seed in $seeds; do
    run="$out/log$k-p$particles-s$seed"
    step "$run.stderr" build/bin/slamer-localizer --config "$out/localizer.yaml" --map "$out/map/map.yaml" \
      --robot config/robots/cmu_wean.yaml --mode lfm --seed "$seed" --global --replay "$out/log$k.lcm" --out "$run.lcm"
    build/bin/slamer-settle "$run.lcm"
  done
  # With several seeds: from which scan the runs agree (settled is not right).
  runs=()
  for seed in $seeds; do runs+=("$out/log$k-p$particles-s$seed.lcm"); done
  if [ "${#runs[@]}" -ge 2 ]; then
    build/bin/slamer-settle --agree 0.5 "${runs[@]}" | sed -n '/^the /,$p'
  fi
done
