#!/usr/bin/env bash
# Peak resident size and run time of slamer-localizer with a 200 m x 200 m map
# at 5 cm (16 million cells): the paper_indoor building tiled 4 x 11 times, the
# first tile where the bundled map has it, so the paper_indoor log localizes in it.
#   test/bench/localizer_memory.sh [BUILD_DIR] [WORK_DIR]
# Prints one line per mode: peak RSS (MB), wall time, and the mean position error.
set -euo pipefail
if [[ ! -x /usr/bin/time ]]; then
  echo "localizer_memory.sh: needs GNU time for the peak RSS (apt-get install time)" >&2
  exit 1
fi
repo="$(cd "$(dirname "$0")/../.." && pwd)"
build="$(cd "${1:-$repo/build}" && pwd)"
work="${2:-$(mktemp -d)}"
mkdir -p "$work/big"
bin="$build/bin"

# The tiled plan: shift every point of the building's shapes; x at even, y at odd positions.
plan="$repo/config/maps/paper_indoor/plan.yaml"
{
  echo "resolution: 0.05"
  echo "size: [200.0, 200.0]"
  echo "origin: [-0.5, -0.5]"
  echo "unknown_background: true"
  echo "free_areas:"
  for ((i = 0; i < 4; i++)); do
    for ((j = 0; j < 11; j++)); do
      echo "  - {box: [$((i * 50)), $((j * 18)), $((i * 50 + 40)), $((j * 18 + 16))]}"
    done
  done
  sed -n '/^classes:/,/^shapes:/p' "$plan"
  for ((i = 0; i < 4; i++)); do
    for ((j = 0; j < 11; j++)); do
      grep -E '^  - \{class: .*points: \[' "$plan" | sed 's/ *#.*$//' |
        awk -v dx=$((i * 50)) -v dy=$((j * 18)) '{
          start = index($0, "points: [") + 9; stop = index($0, "]}");
          n = split(substr($0, start, stop - start), p, ", ");
          out = "";
          for (k = 1; k <= n; k++) out = out (k > 1 ? ", " : "") (p[k] + (k % 2 == 1 ? dx : dy));
          print substr($0, 1, start - 1) out "]}";
        }'
    done
  done
} >"$work/big/plan.yaml"
"$bin/slamer-make-map" "$work/big/plan.yaml" "$work/big" >/dev/null

if [[ ! -f "$work/objects.lcm" ]]; then
  "$bin/slamer-sim" --world "$repo/config/worlds/paper_indoor.yaml" --seed 1 --out "$work/sim.lcm" 2>/dev/null
  "$bin/slamer-recognizer" --config "$repo/config/recognizer.yaml" --replay "$work/sim.lcm" \
    --out "$work/objects.lcm" 2>/dev/null
fi

echo "map: $(identify -format '%w x %h' "$work/big/map.pgm" 2>/dev/null || stat -c '%s bytes' "$work/big/map.pgm")"
for map in "$repo/config/maps/paper_indoor/map.yaml" "$work/big/map.yaml"; do
  for mode in lfm slfm slamer; do
    out="$work/out_${mode}.lcm"
    /usr/bin/time -f '%M %e' -o "$work/time.txt" "$bin/slamer-localizer" --config "$repo/config/localizer.yaml" \
      --map "$map" --mode "$mode" --replay "$work/objects.lcm" --out "$out" 2>/dev/null
    read -r rss_kb seconds <"$work/time.txt"
    error=$("$bin/slamer-eval" --config "$repo/config/eval.yaml" --world "$repo/config/worlds/paper_indoor.yaml" \
      "$out" 2>/dev/null | awk '/Pose error/ {print $7; exit}')
    printf '%-50s %-6s peak RSS %6.1f MB  %6.1f s  mean error %s cm\n' "$(basename "$(dirname "$map")")/$(basename "$map")" \
      "$mode" "$(awk -v kb="$rss_kb" 'BEGIN {print kb / 1024}')" "$seconds" "${error:-?}"
  done
done
