#!/usr/bin/env bash
# Runs slamer-bench on every shared *-corrected CARMEN log (aces, csail,
# fr079) for each seed and prints one line per run (position error mean /
# std / max, heading, fraction lost, CPU time per scan). The reference is
# each log's own GMapping estimate, not ground truth.
#   tools/datasets/bench_shared_logs.sh [OUT_DIR]     (run from the repo root after building)
#   environment: SEEDS ("1 2 3"), BEAMS (all|60), PARTICLES (500), MODE (lfm), DATASETS (folder of the logs)
set -euo pipefail
out=${1:-bench_output}
seeds=${SEEDS:-1 2 3}
beams=${BEAMS:-all}
particles=${PARTICLES:-500}
mode=${MODE:-lfm}
data=${DATASETS:-../shared/datasets/ple_carmen_corrected}
if [ ! -d "$data" ]; then
  echo "bench_shared_logs: $data is absent (set DATASETS)" >&2
  exit 1
fi
mkdir -p "$out"
for log in aces csail freiburg-079; do
  for seed in $seeds; do
    dir="$out/$log-$mode-p$particles-b$beams-s$seed"
    build/bin/slamer-bench --carmen "$data/$log-corrected.log.gz" --particles "$particles" --beams "$beams" \
      --mode "$mode" --seed "$seed" --out "$dir" 2>"$dir.stderr" || { echo "$log seed $seed: failed, see $dir.stderr"; continue; }
    printf '%-13s seed %s: %s\n' "$log" "$seed" "$(grep -o '[0-9]* scans: position error.*per scan[^;]*' "$dir.stderr")"
  done
done
