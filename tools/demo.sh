#!/usr/bin/env bash
# The demo: installs what is missing, builds, and runs the stack on the
# simulated i-Cart mini in the paper-like building. slamer-sim publishes live
# on LCM (at --speed 2), slamer-recognizer and slamer-localizer run as
# separate processes, the real lcm-logger records every channel. Then the
# recorded sensor data goes through the offline lfm, slfm and slamer modes
# (same seed and particles), slamer-eval prints the paper's table and
# slamer-render draws the run. Usage: tools/demo.sh [OUTPUT_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mkdir -p "${1:-$root/demo_output}" && cd "${1:-$root/demo_output}" && pwd)
build=$root/build
bin=$build/bin
world=$root/config/worlds/paper_indoor.yaml
url="udpm://239.255.76.67:7667?ttl=0"

"$root/tools/setup.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)" >/dev/null
echo "demo: built; output goes to $out"

pids=()
cleanup() { for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

rm -f "$out"/*.lcm
lcm-logger --lcm-url="$url" -f "$out/live.lcm" >"$out/logger.log" 2>&1 & pids+=($!)
"$bin/slamer-recognizer" --config "$root/config/recognizer.yaml" --lcm-url "$url" 2>"$out/recognizer.log" & pids+=($!)
"$bin/slamer-localizer" --config "$root/config/localizer.yaml" --lcm-url "$url" 2>"$out/localizer.log" & pids+=($!)
sleep 1
echo "demo: driving 167 m through the building at twice real time (about 160 s); watch it with build/bin/slamer-spy"
"$bin/slamer-sim" --world "$world" --config "$root/config/sim.yaml" --seed 1 --speed 2 --lcm-url "$url" 2>"$out/sim.log" &
sim=$!
sleep 5
"$bin/slamer-status" --lcm-url "$url" --once 2 --expect slamer-sim,slamer-recognizer,slamer-localizer || true
wait "$sim"
sleep 1
cleanup
pids=()
trap - EXIT

echo "demo: the same sensor data through the three localizers offline (500 particles, seed 1)"
"$bin/slamer-recognizer" --config "$root/config/recognizer.yaml" --replay "$out/live.lcm" --out "$out/recognized.lcm"
for mode in lfm slfm slamer; do
  "$bin/slamer-localizer" --config "$root/config/localizer.yaml" --mode "$mode" --seed 1 \
    --replay "$out/recognized.lcm" --out "$out/$mode.lcm" &
done
wait
"$bin/slamer-eval" --world "$world" --config "$root/config/eval.yaml" --plot "$out/errors.png" \
  "$out/lfm.lcm" "$out/slfm.lcm" "$out/slamer.lcm" "$out/live.lcm" | tee "$out/table.txt"
"$bin/slamer-eval" --world "$world" --config "$root/config/eval.yaml" --json \
  "$out/lfm.lcm" "$out/slfm.lcm" "$out/slamer.lcm" "$out/live.lcm" > "$out/table.json"
"$bin/slamer-render" --world "$world" --out "$out/frames" --every 200 "$out/slamer.lcm"
echo
echo "demo: done. live log $out/live.lcm (replay: lcm-logplayer --lcm-url=$url $out/live.lcm)"
echo "      table $out/table.txt ($out/table.json), error plot $out/errors.png, frames $out/frames/"
