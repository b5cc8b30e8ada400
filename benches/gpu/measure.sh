#!/usr/bin/env bash
# Issue 34, item 5: the intact jointed step on a lent GPU machine, CPU
# (all its cores) against stage 1 on the GPU, at 1e5 and 1e6 tets.
#
# Prepare here (the device machine has no network and may lack the Vulkan
# loader):
#   cargo build --release -p femdem-benches --example gpu_step
#   mkdir -p target/gpu-carry && cp target/release/examples/gpu_step target/gpu-carry/ \
#     && cp /usr/lib/x86_64-linux-gnu/libvulkan.so.1 target/gpu-carry/
# then run `benches/gpu/measure.sh` there with carry = ["target/gpu-carry"].
# It prints what Vulkan finds and both rates; under ten minutes on an H100
# machine (the 1e6-tet box takes about a minute to build on 16 cores).
set -u
cd "$(dirname "$0")/../.."
carry=target/gpu-carry
export LD_LIBRARY_PATH="$PWD/$carry${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
nvidia-smi -L 2>&1 | head -4
echo "ICD files:"; ls /usr/share/vulkan/icd.d /etc/vulkan/icd.d 2>&1
# The NVIDIA driver's Vulkan part is libGLX_nvidia.so.0; where the driver
# package installed no ICD file, point the loader at it.
if ! ls /usr/share/vulkan/icd.d/nvidia* /etc/vulkan/icd.d/nvidia* > /dev/null 2>&1; then
    lib=$(ldconfig -p 2>/dev/null | awk '/libGLX_nvidia.so.0/ {print $NF; exit}')
    if [ -n "$lib" ]; then
        printf '{"file_format_version":"1.0.0","ICD":{"library_path":"%s","api_version":"1.3.0"}}\n' "$lib" \
            > "$carry/nvidia_icd.json"
        export VK_ICD_FILENAMES="$PWD/$carry/nvidia_icd.json"
        echo "no NVIDIA ICD file: using $lib"
    fi
fi
threads=$(nproc)
for tets in 100000 1000000; do
    echo "== $tets tets, $threads threads"
    RAYON_NUM_THREADS=$threads timeout 280 "$carry/gpu_step" "$tets" 100 2>&1 | grep -v XDG_RUNTIME_DIR
done
