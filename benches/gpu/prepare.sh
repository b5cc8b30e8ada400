#!/usr/bin/env bash
# Builds what benches/gpu/measure.sh runs on a lent GPU machine (no
# network there, and maybe no Vulkan loader) into target/gpu-carry:
# the gpu_step example, the femdem binary (both stripped, to stay within
# the 64 MiB a run may carry) and the Vulkan loader. Then run
#   benches/gpu/measure.sh
# there with carry = ["target/gpu-carry"]. Run from anywhere in the
# repository.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -p femdem-benches --example gpu_step
cargo build --release -p femdem-cli
mkdir -p target/gpu-carry
cp target/release/examples/gpu_step target/release/femdem target/gpu-carry/
strip target/gpu-carry/gpu_step target/gpu-carry/femdem
loader=/usr/lib/x86_64-linux-gnu/libvulkan.so.1
[ -e "$loader" ] || { echo "no Vulkan loader at $loader: install Debian's libvulkan1" >&2; exit 1; }
cp -L "$loader" target/gpu-carry/
du -sh target/gpu-carry
