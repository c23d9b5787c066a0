#!/bin/bash
# The CUDA backend's checks and figures on a machine with an NVIDIA GPU (docs/benchmarks.md,
# "Issue 13"): the GPU tests, our BVH's ray throughput, and the frame targets, each frame's cost
# with the quality it buys. Usage: scripts/gpu_bench.sh [BUILD_DIR] [OUT_DIR]
# BUILD_DIR (default build/release) holds bounce, tests/bounce_gpu_tests and
# bench/bounce_gpu_microbench, built with nvcc; OUT_DIR (default gpu-bench) gets the logs and
# images.
set -u
build=${1:-build/release}
out=${2:-gpu-bench}
mkdir -p "$out"
bounce="$build/bounce"
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee "$out/gpu.txt"

echo "== GPU tests"
"$build/tests/bounce_gpu_tests" 2>&1 | tee "$out/gpu_tests.txt" | tail -25

echo "== BVH ray throughput on the GPU"
"$build/bench/bounce_gpu_microbench" --benchmark_min_time=0.5 2>&1 | tee "$out/gpu_rays.txt"

echo "== Seed 000's setting: Cornell 1920x1080, 1,000 photon paths, one bounce"
"$bounce" bench cornell --device cuda --no-denoise -W 1920 -H 1080 --photons 1000 --bounces 1 \
  --warmup 10 -n 200 2>&1 | tee "$out/frame_seed000.txt"

# The radius: 1% of the diagonal. The default 3%, chosen for 2,000 paths, makes each gather point
# read thousands of photons for no better image (docs/benchmarks.md, "1M photon paths").
echo "== 1920x1080, 1M photon paths, multi-bounce, hash-grid gather, radius 1%"
"$bounce" bench cornell --device cuda --no-denoise -W 1920 -H 1080 --photons 1000000 \
  --bounces -1 --gather grid --radius 1% --warmup 5 -n 50 2>&1 | tee "$out/frame_1m.txt"

echo "== The real-time frame at 512x512 on both backends (tiled, 2,000 paths): cost"
for device in cuda cpu; do
  "$bounce" bench cornell --device "$device" --no-denoise --warmup 5 -n 50 2>&1 |
    tee "$out/frame512_$device.txt" | grep -E "total|frame"
done

echo "== The same frame's image on both backends, and their difference"
for device in cuda cpu; do
  "$bounce" render cornell --device "$device" --no-denoise --spp 1 --photons 2000 \
    --light-samples 1 -o "$out/frame512_$device.exr" 2>&1 | tail -1
done
"$bounce" compare "$out/frame512_cpu.exr" "$out/frame512_cuda.exr" 2>&1 |
  tee "$out/compare_cpu_cuda.txt"
