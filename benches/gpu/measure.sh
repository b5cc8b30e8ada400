#!/usr/bin/env bash
# Issue 34, item 5, and issue 35's first numbers, on a lent GPU machine:
# the intact jointed step at 1e5 and 1e6 tets, CPU (all its cores)
# against the resident step on the GPU (`gpu_step`); then the README run
# over its intact phase (platens in contact, contact on the CPU beside the
# device) and the multi-layer quick case over 100 steps (pre-existing
# fractures in contact from step 1), `femdem run` on the CPU and with
# `--device gpu`, each printing its throughput.
#
# Prepare here with benches/gpu/prepare.sh (the device machine has no
# network and may lack the Vulkan loader), then run `benches/gpu/measure.sh`
# there with carry = ["target/gpu-carry"]. It prints what Vulkan finds and
# every rate; under ten minutes on an H100 machine (the 1e6-tet box takes
# about a minute to build on 16 cores).
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
# Time limits add up to 530 s, inside one device command's 600 s.
for run in "100000 90" "1000000 200"; do
    read -r tets limit <<< "$run"
    echo "== $tets tets, $threads threads"
    RAYON_NUM_THREADS=$threads timeout "$limit" "$carry/gpu_step" "$tets" 100 2>&1 | grep -v XDG_RUNTIME_DIR
    status=${PIPESTATUS[0]}
    [ "$status" = 0 ] || echo "gpu_step $tets: exit status $status (124: over ${limit} s)"
done
# output.interval = 1 s: no frames but the first and last (the windows
# are shorter), so that writing does not enter the timing.
femdem="$carry/femdem"
for run in "cases/brazilian-split.toml solver.end_time=3e-4" "cases/paper/multilayer.toml solver.end_time=5.7e-5"; do
    read -r case window <<< "$run"
    for device in cpu gpu; do
        echo "== femdem run $case --set $window --device $device, $threads threads"
        timeout 60 "$femdem" run "$case" --out "/tmp/measure-$device" --overwrite --device "$device" \
            --threads "$threads" --set "$window" --set output.interval=1.0 2>&1 \
            | grep -E "^femdem: |^error|finished after|wall time|throughput|bytes a step" | grep -v XDG_RUNTIME_DIR
        status=${PIPESTATUS[0]}
        [ "$status" = 0 ] || echo "femdem run: exit status $status (124: over 60 s)"
    done
done
