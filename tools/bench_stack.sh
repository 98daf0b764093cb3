#!/usr/bin/env bash
# End-to-end figures of the whole stack (issue 15; a benchmark, not a test):
# config/launch/icart_mini_sim.yaml through slamer-launch (the simulated
# i-Cart mini through the real drivers, recognizer and localizer over LCM
# multicast), lcm-logger recording everything, the paper-like world's path
# driven LAPS times at real time (2 laps: about 10.5 min). Then slamer-latency
# prints latency and losses from the log, and this script the CPU and memory of
# every process, read from /proc from 30 s after the start to the end.
# Usage: tools/bench_stack.sh [OUTPUT_DIR] [LAPS]   (needs a built build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mkdir -p "${1:-$root/bench_output}" && cd "${1:-$root/bench_output}" && pwd)
laps=${2:-2}
bin=$root/build/bin
[ -x "$bin/slamer-launch" ] && [ -x "$bin/slamer-latency" ] || { echo "bench_stack: build first (tools/test.sh)" >&2; exit 1; }

# The shipped launch file with absolute paths and the laps added.
launch=$out/icart_mini_sim_bench.yaml
sed -e "s#\.\./#$root/config/#g" -e "s#--seed, \"1\"\]#--seed, \"1\", --laps, \"$laps\"]#" \
  -e "s#\${log_dir}/icart_mini_sim.lcm#$out/stack.lcm#" "$root/config/launch/icart_mini_sim.yaml" >"$launch"
grep -q -- "--laps" "$launch" || { echo "bench_stack: could not add --laps to the sim's args" >&2; exit 1; }
rm -f "$out"/stack.lcm*  # lcm-logger -i appends .00 (and .01, ... to keep what exists)

programs=(slamer-urg-sim slamer-tfrog-sim slamer-urg slamer-wheels slamer-recognizer slamer-localizer slamer-sim lcm-logger)
ticks=$(getconf CLK_TCK)
declare -A first_ticks last_ticks peak_kb pids first_at
# CPU ticks (user + system) and peak resident memory of PID: "TICKS KB".
sample() { awk '{print $14 + $15}' "/proc/$1/stat" 2>/dev/null | tr '\n' ' ' && awk '/VmHWM/ {print $2}' "/proc/$1/status" 2>/dev/null; }
find_pid() { pgrep -n -f "^[^ ]*$1( |$)" || true; }

"$bin/slamer-launch" "$launch" --enable logger --log-dir "$out/logs" >"$out/launch.log" 2>&1 &
launcher=$!
trap 'kill -INT $launcher 2>/dev/null || true; wait $launcher 2>/dev/null || true' EXIT
echo "bench_stack: running $laps laps of paper_indoor at real time; logs in $out/logs"
sleep 30
first_time=$(date +%s.%N)
last_time=$first_time
while kill -0 "$launcher" 2>/dev/null; do
  for p in "${programs[@]}"; do
    pid=$(find_pid "$p")
    [ -n "$pid" ] || continue
    read -r t kb < <(sample "$pid") || continue
    if [ "${pids[$p]:-}" != "$pid" ]; then  # first seen, or restarted: start its interval again
      pids[$p]=$pid first_ticks[$p]=$t first_at[$p]=$(date +%s.%N)
    fi
    last_ticks[$p]=$t peak_kb[$p]=$kb
  done
  last_time=$(date +%s.%N)
  sleep 5
done
trap - EXIT
wait "$launcher" || echo "bench_stack: slamer-launch exited with $? (see $out/launch.log)"

echo "== per process, from 30 s after the start to the end ($(awk -v a="$first_time" -v b="$last_time" 'BEGIN {printf "%.0f", b - a}') s)"
printf "%-20s %8s %12s\n" process "CPU [%]" "peak RSS [MB]" | tee "$out/processes.txt"
for p in "${programs[@]}"; do
  [ -n "${pids[$p]:-}" ] || { printf "%-20s %8s\n" "$p" "not seen" | tee -a "$out/processes.txt"; continue; }
  awk -v n="$p" -v t0="${first_ticks[$p]}" -v t1="${last_ticks[$p]}" -v hz="$ticks" -v a="${first_at[$p]}" \
    -v b="$last_time" -v kb="${peak_kb[$p]}" \
    'BEGIN {printf "%-20s %8.2f %12.1f\n", n, 100 * (t1 - t0) / hz / (b - a), kb / 1024}' | tee -a "$out/processes.txt"
done
log=$(ls "$out"/stack.lcm* | head -n 1)
echo "== latency and losses (build/bin/slamer-latency $log)"
"$bin/slamer-latency" "$log" | tee "$out/latency.txt"
"$bin/slamer-latency" --json "$log" >"$out/latency.json"
