#!/bin/bash
# CPU of slamer-wheels streaming 200 Hz odometry from slamer-tfrog-sim, over
# SECONDS (default 60) after a 3 s warm-up. Run from the checkout root after
# building slamer-wheels and slamer-tfrog-sim into build/.
set -euo pipefail
seconds=${1:-60}
bin=build/bin
link=/tmp/slamer_cpu_tfrog_$$
"$bin/slamer-tfrog-sim" --link "$link" --duration $((seconds + 15)) > /dev/null 2>&1 &
sim=$!
sleep 0.3
"$bin/slamer-wheels" --config config/wheels.yaml --device "$link" --lcm-url "udpm://239.255.76.67:7681?ttl=0" \
  > /tmp/slamer_cpu_wheels_$$.log 2>&1 &
wheels=$!
sleep 3
read -r u0 s0 < <(awk '{print $14, $15}' "/proc/$wheels/stat")
t0=$(date +%s.%N)
sleep "$seconds"
read -r u1 s1 < <(awk '{print $14, $15}' "/proc/$wheels/stat")
t1=$(date +%s.%N)
kill -INT "$wheels"; wait "$wheels" || true
kill "$sim" 2>/dev/null || true
awk -v u=$((u1 - u0)) -v s=$((s1 - s0)) -v hz="$(getconf CLK_TCK)" -v t0="$t0" -v t1="$t1" \
  'BEGIN { printf "slamer-wheels: user %.2f s, system %.2f s over %.1f s wall = %.2f %% of one core\n", u/hz, s/hz, t1-t0, 100*(u+s)/hz/(t1-t0) }'
