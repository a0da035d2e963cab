#!/usr/bin/env bash
# Packs what bench/gpu_bench.sh needs on a lent GPU machine, which starts bare and reaches no network:
# stripped `vots` and `render_bench` with the shared libraries they load (not glibc's or the C++ runtime's,
# which the machine has newer, nor GL's, which its driver gives through glvnd), and Debian's glvnd loader
# packages to unpack there. Prints the device command that runs gpu_bench.sh there and brings its logs back.
#
# Usage: bench/gpu_bundle.sh [BUILD_DIR]   (default build/release, else build/ci)
# Writes bench/out/gpu-bundle (ignored by git). Then, with the device tool:
#   run(carry=["bench/out/gpu-bundle", "data"], timeout_s=580, command=<the printed line>)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-}
if [ -z "$build" ]; then
    for candidate in build/release build/ci; do
        if [ -x "$candidate/cli/vots" ] && [ -x "$candidate/bench/render_bench" ]; then
            build=$candidate
            break
        fi
    done
fi
if [ -z "$build" ] || [ ! -x "$build/cli/vots" ] || [ ! -x "$build/bench/render_bench" ]; then
    echo "gpu_bundle.sh: no build with cli/vots and bench/render_bench (cmake --workflow --preset release)" >&2
    exit 1
fi
[ -f data/cranium.nhdr ] || { echo "gpu_bundle.sh: data/cranium.nhdr is missing: run scripts/fetch-ct" >&2; exit 1; }

bundle=bench/out/gpu-bundle
rm -rf "$bundle"
mkdir -p "$bundle/build/cli" "$bundle/build/bench" "$bundle/lib" "$bundle/gl"
strip -o "$bundle/build/cli/vots" "$build/cli/vots"
strip -o "$bundle/build/bench/render_bench" "$build/bench/render_bench"
ldd "$build/cli/vots" "$build/bench/render_bench" | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u |
    grep -Ev '/(libc|libm|libdl|libpthread|librt|libresolv|libstdc\+\+|libgcc_s|ld-linux[^/]*)\.so|/lib(EGL|GL|GLX|GLdispatch|OpenGL|gbm|drm)\.so' |
    while read -r lib; do cp -L "$lib" "$bundle/lib/"; done
# libepoxy opens libEGL.so.1 at run time: glvnd's, which picks the NVIDIA vendor library.
(cd "$bundle/gl" && apt-get download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null 2>&1) ||
    { echo "gpu_bundle.sh: apt-get download of the glvnd packages failed" >&2; exit 1; }
echo "gpu_bundle.sh: $(du -sh "$bundle" | cut -f1) in $bundle from $build (data/ travels beside it: $(du -sh data | cut -f1))" >&2

# The device command (at most 2000 characters): glvnd unpacked, the NVIDIA EGL vendor named where the
# machine keeps it, the bench, and its logs (not the fits' cache) back in one archive.
cat <<'CMD'
for f in bench/out/gpu-bundle/gl/*.deb; do dpkg -x $f /; done; ldconfig; v=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json; [ -f $v ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$v; export LD_LIBRARY_PATH=$PWD/bench/out/gpu-bundle/lib; nvidia-smi -L; BUILD=bench/out/gpu-bundle/build timeout 540 bash bench/gpu_bench.sh /tmp/gpu >/tmp/gpu.txt 2>&1; echo "gpu_bench exit $?"; tail -80 /tmp/gpu.txt; tar czf $OUT/gpu.tgz --exclude=cache -C /tmp gpu gpu.txt
CMD
