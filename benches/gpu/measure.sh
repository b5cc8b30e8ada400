#!/usr/bin/env bash
# Issues 34 (item 5) and 35 on a lent GPU machine: the intact jointed
# step at 1e5 and 1e6 tets, CPU (all its cores) against the resident step
# on the GPU (`gpu_step`); then the README run over its intact phase
# (platens in contact), the paper's Brazilian disc (1.2 mm, extruded) over
# its first 20 µs and the multi-layer quick case over 100 steps
# (pre-existing fractures in contact from step 1), `femdem run` on the CPU
# and with `--device gpu` (the contact pass on the CPU, the pairs' Eq. 17
# on the device), each printing its throughput.
#
# Prepare here with benches/gpu/prepare.sh (the device machine has no
# network and may lack the Vulkan loader and libglvnd: prepare.sh fetches
# their Debian packages into .gl/), then run `benches/gpu/measure.sh`
# there with carry = ["target/gpu-carry", ".gl"]. It prints what Vulkan
# finds and every rate, and copies its output to $OUT/measure.log where
# $OUT is set.
#
# Arguments choose the parts (default `bulk contact`): `bulk` the
# gpu_step boxes, `contact` the three contact cases and the fragmented
# cube (`gpu_contact`: CPU and device by stage, and the pair kernel timed
# alone on the pass's last list), `fragmented` the cube alone, `paper` the
# multi-layer case at the paper's mesh size (24 mm, 603k tets) over its
# first 40 steps (a minute or two of meshing each, on the CPU and on the
# device). Every run prints its host wall-clock time by stage, and the
# device runs their read-backs' host time by part. DEVICES=gpu (or cpu)
# runs the `femdem run` parts on that side alone.
set -u
cd "$(dirname "$0")/../.."
parts=" ${*:-bulk contact} "
case ${DEVICES:-cpu gpu} in
    cpu | gpu | "cpu gpu" | "gpu cpu") ;;
    *) echo "measure.sh: DEVICES='$DEVICES' is not cpu, gpu or both" >&2; exit 2 ;;
esac
for part in $parts; do
    case $part in
        bulk | contact | fragmented | paper) ;;
        *) echo "measure.sh: unknown part '$part' (bulk, contact, fragmented, paper)" >&2; exit 2 ;;
    esac
done
log=${OUT:-/tmp}/measure.log
measure() {
carry=target/gpu-carry
# Debian's libvulkan1 and libglvnd packages (the NVIDIA Vulkan driver,
# libGLX_nvidia, needs libGLdispatch), unpacked where the machine lacks them.
if [ -d .gl ] && ! ldconfig -p | grep -q libGLdispatch.so.0; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
    echo "unpacked $(ls .gl | wc -l) packages from .gl"
fi
export LD_LIBRARY_PATH="$PWD/$carry${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
nvidia-smi -L 2>&1 | head -4
echo "ICD files:"; ls /usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/nvidia/share/vulkan/icd.d 2>&1
# Where the driver's ICD file is not in the loader's search path, name it;
# where there is none at all, write one for libGLX_nvidia.so.0 (the
# driver's Vulkan part).
icd=""
for f in /usr/share/vulkan/icd.d/nvidia*.json /etc/vulkan/icd.d/nvidia*.json /usr/local/nvidia/share/vulkan/icd.d/nvidia*.json; do
    [ -e "$f" ] && { icd=$f; break; }
done
if [ -z "$icd" ]; then
    lib=$(ldconfig -p 2>/dev/null | awk '/libGLX_nvidia.so.0/ {print $NF; exit}')
    if [ -n "$lib" ]; then
        icd="$PWD/$carry/nvidia_icd.json"
        printf '{"file_format_version":"1.0.0","ICD":{"library_path":"%s","api_version":"1.3.0"}}\n' "$lib" > "$icd"
    fi
fi
if [ -n "$icd" ]; then
    export VK_DRIVER_FILES="$icd" VK_ICD_FILENAMES="$icd"
    echo "Vulkan driver file: $icd"
fi
threads=$(nproc)
# A first small box: is the device there, and does f64 run on it?
RAYON_NUM_THREADS=$threads timeout 40 "$carry/gpu_step" 2000 10 2>&1 | grep -v XDG_RUNTIME_DIR
# Time limits: the first box 40 s, bulk 180 s (360 s with a baseline),
# contact 240 s (of which the fragmented cube, also the part `fragmented`
# alone, 60 s), paper 300 s; DEVICES=gpu (or cpu) halves the `femdem run`
# parts' (paper alone: 110 s on an H200, meshing included). Within one
# command's 600 s: `bulk contact`
# without a baseline (460 s), `bulk` with one (400 s), `contact` (280 s),
# `paper` alone (340 s; 230 s on an H100, meshing included); with a
# baseline run `bulk` and `contact` as two calls, or accept that the
# limits could add up to 640 s (bulk and contact took 55-90 s in all on
# an H200 and an H100).
# A baseline build of the example, if prepared as gpu-carry/gpu_step_base
# (an earlier commit's), runs before this one's at each size: the same
# machine's ratio of the two.
steppers=gpu_step
[ -x "$carry/gpu_step_base" ] && steppers="gpu_step_base gpu_step"
runs=()
[[ " $parts " == *" bulk "* ]] && runs=("100000 60" "1000000 120")
if [[ " $parts " == *" contact "* || " $parts " == *" fragmented "* ]]; then
    echo "== gpu_contact 3400 100, $threads threads"
    RAYON_NUM_THREADS=$threads timeout 60 "$carry/gpu_contact" 3400 100 "$carry/cube50_3400.snap" 2>&1 \
        | grep -v XDG_RUNTIME_DIR
    status=${PIPESTATUS[0]}
    [ "$status" = 0 ] || echo "gpu_contact: exit status $status (124: over 60 s)"
fi
for run in ${runs[@]+"${runs[@]}"}; do
    read -r tets limit <<< "$run"
    for stepper in $steppers; do
        echo "== $stepper, $tets tets, $threads threads"
        RAYON_NUM_THREADS=$threads timeout "$limit" "$carry/$stepper" "$tets" 100 2>&1 | grep -v XDG_RUNTIME_DIR
        status=${PIPESTATUS[0]}
        [ "$status" = 0 ] || echo "$stepper $tets: exit status $status (124: over ${limit} s)"
    done
done
# output.interval = 1 s: no frames but the first and last (the windows
# are shorter), so that writing does not enter the timing.
femdem="$carry/femdem"
runs=()
[[ " $parts " == *" contact "* ]] && runs+=("30 cases/brazilian-split.toml solver.end_time=3e-4" \
    "30 cases/paper/brazilian.toml solver.end_time=2e-5" "30 cases/paper/multilayer.toml solver.end_time=5.7e-5")
[[ " $parts " == *" paper "* ]] && runs+=("150 cases/paper/multilayer.toml solver.end_time=7.8e-6 mesh.parts.0.element_size=0.024")
for run in ${runs[@]+"${runs[@]}"}; do
    # The time limit, the case, then its overrides (one word each).
    read -r limit case overrides <<< "$run"
    sets=(--set output.interval=1.0)
    for o in $overrides; do sets+=(--set "$o"); done
    for device in ${DEVICES:-cpu gpu}; do
        echo "== femdem run $case ${sets[*]} --device $device, $threads threads"
        start=$SECONDS
        # A run stopped by SIGTERM writes its checkpoint first: killed 10 s
        # later if that takes longer.
        timeout -k 10 "$limit" "$femdem" run "$case" --out "/tmp/measure-$device" \
            --overwrite --device "$device" --threads "$threads" "${sets[@]}" 2>&1 \
            | grep -E "^femdem: [0-9]|^femdem: warning|^error|finished after|^interrupted|^ended|^fractures|wall time|throughput|^device|^stages|^read-backs" \
            | grep -v XDG_RUNTIME_DIR
        status=${PIPESTATUS[0]}
        echo "elapsed $((SECONDS - start)) s, meshing and start included"
        [ "$status" = 0 ] || echo "femdem run: exit status $status (124 or 137: over $limit s)"
    done
done
}
# Everything it prints, also into the log (the pipeline waits for tee).
measure 2>&1 | tee "$log"
