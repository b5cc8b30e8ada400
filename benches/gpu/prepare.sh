#!/usr/bin/env bash
# Builds what benches/gpu/measure.sh runs on a lent GPU machine (no
# network there, and maybe no Vulkan loader) into target/gpu-carry:
# the gpu_step and gpu_contact examples, the femdem binary (stripped, to stay within
# the 64 MiB a run may carry) and the Vulkan loader; and fetches Debian's
# libvulkan1 and libglvnd packages into .gl/ (the NVIDIA driver's Vulkan
# part needs libGLdispatch; measure.sh unpacks them where missing). Then
# run
#   benches/gpu/measure.sh
# there with carry = ["target/gpu-carry", ".gl"]. With a path as its
# argument (an earlier build of the gpu_step example), that build is
# carried as gpu_step_base and measured beside this one. Run from
# anywhere in the repository.
set -euo pipefail
# The baseline's path, made absolute before moving to the repository root.
base=${1:+$(realpath "$1")}
cd "$(dirname "$0")/../.."
cargo build --release -p femdem-benches --example gpu_step --example gpu_contact
cargo build --release -p femdem-cli
mkdir -p target/gpu-carry
cp target/release/examples/gpu_step target/release/examples/gpu_contact target/release/femdem target/gpu-carry/
strip target/gpu-carry/gpu_step target/gpu-carry/gpu_contact target/gpu-carry/femdem
loader=/usr/lib/x86_64-linux-gnu/libvulkan.so.1
[ -e "$loader" ] || { echo "no Vulkan loader at $loader: install Debian's libvulkan1" >&2; exit 1; }
cp -L "$loader" target/gpu-carry/
# The fragmented cube's state at step 3400 for gpu_contact (made here by a
# first run, ~20 s on 2 cores, so that the device machine need not).
target/release/examples/gpu_contact 3400 0 > /dev/null
cp target/contact_profile/cube50_3400.snap target/gpu-carry/
rm -f target/gpu-carry/gpu_step_base
if [ -n "$base" ]; then
    cp "$base" target/gpu-carry/gpu_step_base
    strip target/gpu-carry/gpu_step_base
fi
# The packages, fetched into a fresh folder and moved into place only when
# all came (an interrupted fetch leaves no half-filled .gl behind).
if ! ls .gl/libglvnd0_*.deb > /dev/null 2>&1; then
    exclude=$(git rev-parse --git-path info/exclude)
    mkdir -p "$(dirname "$exclude")"
    grep -qx '/.gl/' "$exclude" 2>/dev/null || echo '/.gl/' >> "$exclude"
    fetched=$(mktemp -d)
    mkdir -p /tmp/amd64/partial
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    # shellcheck disable=SC2086
    apt-get $o update > /dev/null
    # shellcheck disable=SC2086
    (cd "$fetched" && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
    rm -rf .gl
    mv "$fetched" .gl
    chmod 755 .gl
fi
du -sh target/gpu-carry .gl
