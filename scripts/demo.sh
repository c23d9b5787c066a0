#!/usr/bin/env bash
# The main job: install dependencies, build Release, render the built-in Cornell box to
# out/cornell.png and print the per-stage timings.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release
./build/release/bounce render cornell --out out/cornell.png "$@"
