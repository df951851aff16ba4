#!/usr/bin/env bash
# Packs built binaries with the libraries they load, so they run on another x86-64 Linux machine (an Ubuntu image with
# NVIDIA's driver and no package access). Run from the project root after a build:
#   scripts/gpu-bundle.sh build/default/bin key_identity_tests vulkan_backend_tests vulkan_benchmark
# It writes .gpu-bundle/ (ignored by git through .git/info/exclude). Copy that folder to the GPU machine, then:
#   bash .gpu-bundle/run.sh key_identity_tests --gtest_brief=1
# run.sh unpacks once, points the Vulkan loader at NVIDIA's driver and runs the binary with the host's glibc.
# Adds Debian's libglvnd libraries: NVIDIA's Vulkan driver needs them and the image has none.
set -euo pipefail
bin=$1; shift
[ $# -gt 0 ] || { echo "usage: gpu-bundle.sh BIN_DIR BINARY..." >&2; exit 2; }
out=.gpu-bundle; stage=$(mktemp -d)
mkdir -p "$out" "$stage/bin" "$stage/lib"
grep -qxF '/.gpu-bundle/' .git/info/exclude 2>/dev/null || { mkdir -p .git/info; echo '/.gpu-bundle/' >> .git/info/exclude; }
for b in "$@"; do
  strip -o "$stage/bin/$b" "$bin/$b"
  ldd "$bin/$b" | awk '$3 ~ /^\// {print $3}' | grep -vE '/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*)\.so' | xargs -r -I{} cp -Ln {} "$stage/lib/"
done
cp -Ln "$(ldconfig -p | awk '/libvulkan.so.1 / {print $NF; exit}')" "$stage/lib/"
(cd "$stage" && apt-get download -q libglvnd0 libglx0 libegl1 libgl1 >/dev/null 2>&1 && for d in *.deb; do dpkg -x "$d" glvnd; done &&
  cp -a glvnd/usr/lib/x86_64-linux-gnu/* lib/ && rm -rf glvnd ./*.deb) || echo "gpu-bundle: could not fetch libglvnd (apt-get update first?)" >&2
tar cJf "$out/bundle.tar.xz" -C "$stage" bin lib
rm -rf "$stage"
cat > "$out/run.sh" <<'RUN'
#!/usr/bin/env bash
# usage (on the device machine, from the repo root): bash .gpu-bundle/run.sh BINARY [ARGS...]
here=$(cd "$(dirname "$0")" && pwd); dest=${TMPDIR:-/tmp}/gpu-bundle
[ -d "$dest/bin" ] || { mkdir -p "$dest" && tar xJf "$here/bundle.tar.xz" -C "$dest"; }
icd=$(ls /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json 2>/dev/null | head -n 1)
export VK_ICD_FILENAMES=$icd VK_DRIVER_FILES=$icd LD_LIBRARY_PATH=$dest/lib:/usr/local/nvidia/lib64
b=$1; shift
exec "$dest/bin/$b" "$@"
RUN
chmod +x "$out/run.sh"
du -sh "$out/bundle.tar.xz"
