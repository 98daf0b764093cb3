#!/usr/bin/env bash
# Timing benchmark of slamer-urg (issue 13): the real driver against slamer-urg-sim
# with 0-5 ms uniform reply delay and a drifting device clock, LIDAR utime compared
# with the emulator's truth file. Also the driver's CPU over the run.
#   tools/urg_sim/timing_benchmark.sh [SECONDS=600] [DRIFT_PPM=100] [MODEL=URM-40LC] [INTENSITIES=false]
# Run from the checkout root after building (build/bin).
set -euo pipefail
seconds=${1:-600}
drift=${2:-100}
model=${3:-URM-40LC}
intensities=${4:-false}
bin=build/bin
work=$(mktemp -d)
trap 'kill $sim_pid $driver_pid 2>/dev/null || true; rm -rf "$work"' EXIT
url="udpm://239.255.76.67:$((20000 + $$ % 30000))?ttl=0"
"$bin/slamer-urg-sim" --model "$model" --jitter-ms 5 --drift-ppm "$drift" --truth "$work/truth.csv" \
  --port-file "$work/port" --seed 1 >/dev/null &
sim_pid=$!
for _ in $(seq 100); do [ -s "$work/port" ] && break; sleep 0.05; done
sed "s/intensities: false/intensities: $intensities/" config/urg.yaml >"$work/urg.yaml"
"$bin/slamer-urg" --config "$work/urg.yaml" --host 127.0.0.1 --port "$(cat "$work/port")" --lcm-url "$url" \
  2>"$work/driver.log" &
driver_pid=$!
"$bin/slamer-urg-timing" --lcm-url "$url" --truth "$work/truth.csv" --duration "$seconds" --skip 1 ${BLOCKS:+--blocks "$BLOCKS"}
# CPU of the driver over the run: utime + stime from /proc, in % of one core.
ticks=$(getconf CLK_TCK)
read -r -a stat <"/proc/$driver_pid/stat"
start_ticks=${stat[21]}
boot_uptime=$(cut -d' ' -f1 /proc/uptime)
awk -v u="${stat[13]}" -v s="${stat[14]}" -v st="$start_ticks" -v up="$boot_uptime" -v hz="$ticks" \
  'BEGIN { alive = up - st / hz; printf "slamer-urg CPU: %.2f s user + %.2f s system over %.0f s = %.2f %% of a core\n", u / hz, s / hz, alive, 100 * (u + s) / hz / alive }'
