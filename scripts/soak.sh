#!/usr/bin/env bash
# The soak (issue 14): `bounce bench` plays a dynamic scene (a moving light and a moving object)
# for many frames with each technique, sampling the process's resident memory every K frames
# (bench --memory-every, read from /proc/self/statm), and checks that it stays flat after warm-up.
#
#   scripts/soak.sh [FRAMES] [SIZE] [TECHNIQUE...]   (default: 10000 frames, 64x64; direct tiled vertex lhb)
#
# BOUNCE names the program (default: build/release/bounce), SOAK_SCENE the scene
# (default: scenes/dynamic-cornell.bounce.json), SOAK_WARMUP the warm-up frames (default 200),
# SOAK_EVERY the sampling interval (default 100), SOAK_LIMIT the allowed growth in percent
# (default 1), SOAK_OUT where each technique's bench JSON is written (default build/soak).
# Fails when a technique's peak resident memory after warm-up exceeds the first sample after
# warm-up by more than the limit.
set -euo pipefail
cd "$(dirname "$0")/.."

frames=${1:-10000}
size=${2:-64}
shift 2 || shift $# || true
techniques=("$@")
((${#techniques[@]} > 0)) || techniques=(direct tiled vertex lhb)
bounce=${BOUNCE:-build/release/bounce}
scene=${SOAK_SCENE:-scenes/dynamic-cornell.bounce.json}
warmup=${SOAK_WARMUP:-200}
every=${SOAK_EVERY:-100}
limit=${SOAK_LIMIT:-1}
out=${SOAK_OUT:-build/soak}
mkdir -p "$out"

failed=0
for t in "${techniques[@]}"; do
  json="$out/$t.json"
  start=$SECONDS
  "$bounce" bench "$scene" -t "$t" -W "$size" -H "$size" --animate --warmup "$warmup" \
    --frames "$frames" --memory-every "$every" --json "$json" >"$out/$t.log"
  python3 - "$json" "$t" "$limit" "$((SECONDS - start))" <<'PY' || failed=1
import json, sys
path, technique, limit, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
r = json.load(open(path))
m = r["resident_memory"]
warm = r["warmup_frames"]
after = [b for f, b in zip(m["frames"], m["bytes"]) if f >= warm]
mib = 1024.0 * 1024.0
growth = 100.0 * m["growth_after_warmup"]
print(f"{technique:7s} {r['frames']} frames {r['width']}x{r['height']} in {seconds} s "
      f"({r['fps']:.0f} fps): resident {after[0] / mib:.1f} MiB after warm-up, "
      f"{after[-1] / mib:.1f} at the end, min {min(after) / mib:.1f}, peak {max(after) / mib:.1f} "
      f"({growth:+.2f}%, limit {limit:g}%)")
sys.exit(0 if growth <= limit else 1)
PY
done
exit $failed
