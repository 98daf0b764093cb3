#!/usr/bin/env bash
# Runs slamer-bench on every shared *-corrected CARMEN log (aces, csail,
# fr079) for each seed and prints one line per run (position error mean /
# std / max, heading, fraction lost, CPU time per scan). The reference is
# each log's own GMapping estimate, not ground truth. GLOBAL=1 starts each run
# by global localization instead of at the first reference pose and adds from
# which scan the estimate is right (within 0.5 m to the end) and says OK.
# KIDNAP=1 carries the robot unseen from a quarter of each log's scans to half
# of them (aces 110 -> 220, csail 101 -> 203, fr079 1197 -> 2395) and adds the
# same after the kidnap.
#   tools/datasets/bench_shared_logs.sh [OUT_DIR]     (run from the repo root after building)
#   environment: SEEDS ("1 2 3"), BEAMS (all|60), PARTICLES (500), MODE (lfm), GLOBAL (0|1), KIDNAP (0|1),
#                DATASETS (folder of the logs)
set -euo pipefail
out=${1:-bench_output}
seeds=${SEEDS:-1 2 3}
beams=${BEAMS:-all}
particles=${PARTICLES:-500}
mode=${MODE:-lfm}
global=()
tag=""
if [ "${GLOBAL:-0}" = 1 ]; then
  global=(--global)
  tag="-global"
fi
data=${DATASETS:-../shared/datasets/ple_carmen_corrected}
if [ ! -d "$data" ]; then
  echo "bench_shared_logs: $data is absent (set DATASETS)" >&2
  exit 1
fi
mkdir -p "$out"
declare -A kidnap_scans=([aces]="110 220" [csail]="101 203" [freiburg-079]="1197 2395")
if [ "${KIDNAP:-0}" = 1 ]; then
  tag="$tag-kidnap"
fi
for log in aces csail freiburg-079; do
  kidnap=()
  if [ "${KIDNAP:-0}" = 1 ]; then
    read -r -a kidnap <<<"--kidnap ${kidnap_scans[$log]}"
  fi
  for seed in $seeds; do
    dir="$out/$log-$mode-p$particles-b$beams$tag-s$seed"
    build/bin/slamer-bench --carmen "$data/$log-corrected.log.gz" --particles "$particles" --beams "$beams" \
      --mode "$mode" --seed "$seed" "${global[@]}" "${kidnap[@]}" --out "$dir" 2>"$dir.stderr" ||
      { echo "$log seed $seed: failed, see $dir.stderr"; continue; }
    printf '%-13s seed %s: %s\n' "$log" "$seed" "$(grep -o '[0-9]* scans: position error.*per scan[^;]*' "$dir.stderr")"
    grep -o 'kidnap: .*\|global localization: .*\|after the kidnap: .*' "$dir.stderr" | sed "s/^/$(printf '%-13s seed %s: ' "$log" "$seed")/" || true
  done
done
