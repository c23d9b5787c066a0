#!/bin/sh
# Seed 001's tables 6.1-6.4 on our lhb technique: frame time (ms, mean over N frames after
# warm-up) by triangle count and bounces, direction set, buffer size and paths per pixel.
# Usage: bench/lhb_tables.sh [BOUNCE_BINARY] [FRAMES]   (docs/lhb.md quotes the output)
set -eu
BOUNCE=${1:-build/release/bounce}
N=${2:-5}
row() {  # label, then bench arguments: prints "label | total ms | indirect ms"
  label=$1
  shift
  out=$("$BOUNCE" bench "$@" -t lhb -n "$N" 2>&1)
  total=$(echo "$out" | awk '$1 == "total" {print $2}')
  indirect=$(echo "$out" | awk '$1 == "indirect" {print $2}')
  echo "$label | $total | $indirect"
}
echo "## 6.1 triangles x bounces (512x512, 1 path, 320 directions, 128x128)"
for scene in cornell cubes:1000 cubes:10000 cubes:80000; do
  for b in 1 2 3; do row "$scene bounces=$b" "$scene" --param bounces=$b; done
done
echo "## 6.2 direction sets (cornell, 512x512, 1 path, 2 bounces)"
for set in "0 20" "0 80" "0 320" "1 8" "1 32" "1 128" "3 144" "3 256" "3 320"; do
  set -- $set
  row "set=$1 n=$2" cornell --param direction_set=$1 --param directions=$2
done
echo "## 6.3 buffer size (cornell and cubes:10000, 512x512, 1 path, 2 bounces)"
for scene in cornell cubes:10000; do
  for s in 16 32 64 128 256; do row "$scene size=$s" "$scene" --param size=$s; done
done
echo "## 6.4 paths per pixel (cornell, 512x512, 2 bounces)"
for p in 1 2 4 8 16; do row "paths=$p" cornell --param paths=$p; done
