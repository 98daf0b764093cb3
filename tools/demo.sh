#!/usr/bin/env bash
# The demo: installs what is missing, builds, and runs the whole stack on the
# simulated i-Cart mini in the paper-like building through slamer-launch
# (config/launch/icart_mini_sim.yaml, under Debian's supervisor): slamer-sim
# feeds the SCIP 2.0 and T-frog device emulators, the real slamer-urg and
# slamer-wheels drivers publish LIDAR and ODOMETRY, slamer-recognizer and
# slamer-localizer run live, the real lcm-logger records every channel, all
# separate processes over LCM multicast at real time. Then the recorded
# sensor data goes through the offline lfm, slfm and slamer modes (same seed
# and particles), slamer-eval prints the paper's table, slamer-latency the
# live run's latency and slamer-render draws the run.
# Usage: tools/demo.sh [OUTPUT_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mkdir -p "${1:-$root/demo_output}" && cd "${1:-$root/demo_output}" && pwd)
build=$root/build
bin=$build/bin
world=$root/config/worlds/paper_indoor.yaml
url="udpm://239.255.76.67:7667?ttl=0"  # config/launch/icart_mini_sim.yaml's

"$root/tools/setup.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)" >/dev/null
echo "demo: built; output goes to $out"

rm -f "$out"/*.lcm "$out"/icart_mini_sim.lcm*
echo "demo: the simulated i-Cart mini drives 167 m through the building at real time (about 6 min) under"
echo "      slamer-launch; watch it with build/bin/slamer-spy or build/bin/slamer-status"
# The launch ends by itself when slamer-sim (required, no respawn) has driven its path.
"$bin/slamer-launch" "$root/config/launch/icart_mini_sim.yaml" --enable logger --log-dir "$out"
mv "$(ls "$out"/icart_mini_sim.lcm* | head -n 1)" "$out/live.lcm"  # lcm-logger -i named it .lcm.00

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
"$bin/slamer-latency" "$out/live.lcm" | tee "$out/latency.txt"
"$bin/slamer-render" --world "$world" --out "$out/frames" --every 200 "$out/slamer.lcm"
echo
echo "demo: done. live log $out/live.lcm (replay: lcm-logplayer --lcm-url=$url $out/live.lcm)"
echo "      table $out/table.txt ($out/table.json), latency $out/latency.txt, error plot $out/errors.png,"
echo "      frames $out/frames/, each process's log $out/NAME.log"
