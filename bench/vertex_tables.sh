#!/bin/sh
# Seed 004's experiments on our vertex technique (docs/vertex.md quotes the output): table 6.1
# (frame rate by photons x triangles), table 6.2 (accumulation frames against frame rate and
# photon renewal time), the flashlight demo, a large level and the issue's targets.
# Usage: bench/vertex_tables.sh [BOUNCE_BINARY] [FRAMES] [SMALL_MAP] [LARGE_MAP]
set -eu
BOUNCE=${1:-build/release/bounce}
N=${2:-10}
B=/usr/share/games/openarena/baseoa
SMALL=${3:-$B/pak1-maps.pk3:maps/oa_dm4.bsp}
LARGE=${4:-$B/pak6-patch085.pk3:maps/ctf_compromise.bsp}
SIZE="-W 640 -H 360"
# The flashlight at a strength that shows in a level tens of metres across (docs/vertex.md).
FLASH="--flashlight --flashlight-intensity 1000"
# Photons counted as the seed counts them: one stored photon per path (a single bounce split
# into one direction, no roulette tail), so photons_from_light x accumulation_frames photons
# in the map.
ONE="--param diffuse_reflections=1 --param recursion_depth=1 --param roulette=false"
bench() {  # bench arguments; prints the output
  "$BOUNCE" bench -t vertex -n "$N" --warmup 3 "$@" 2>&1
}
total() { awk '$1 == "total" {print $2}'; }
fps() { awk '$1 == "frame" && $2 == "rate" {print $3}'; }
stage() { awk -v s="$1" '$1 == s {print $2}'; }

echo "## 6.1 frame rate (fps) by photons in the map (columns) and triangles added (rows), $SMALL, 640x360"
echo "refined \\ photons | 400 | 800 | 1600 | 3200 | 6400 | 12800 | 25600"
for t in 0 400 1600 6400 25600; do
  line="$t"
  for p in 400 800 1600 3200 6400 12800 25600; do
    f=$(bench "$SMALL" $SIZE $ONE --param accumulation_frames=1 --param photons_from_light=$p \
      --param mesh_refinement=$t | fps)
    line="$line | $f"
  done
  echo "$line"
done

echo "## 6.2 accumulation frames, 10,000 photons in the map, $SMALL, 640x360, 10,000 added triangles"
echo "frames | fps | renewal time s"
for a in 1 2 4 8 16 32 64; do
  f=$(bench "$SMALL" $SIZE $ONE --param accumulation_frames=$a \
    --param photons_from_light=$((10000 / a)) | fps)
  echo "$a | $f | $(echo "$a $f" | awk '{printf "%.2f", $1 / $2}')"
done

echo "## flashlight demo: 100 photon paths, 9 reflections, depth 1, ~10K triangles, $SMALL"
bench "$SMALL" $SIZE $FLASH --param photons_from_light=100 --param diffuse_reflections=9 \
  --param recursion_depth=1 --param mesh_refinement=6000

echo "## large level: $LARGE, defaults, 640x360"
bench "$LARGE" $SIZE $FLASH

echo "## targets: $SMALL with the flashlight and its own lights, >= 10,000 photons per frame"
for size in "-W 640 -H 360" "-W 1280 -H 720"; do
  bench "$SMALL" $size $FLASH --param photons_from_light=350
done
