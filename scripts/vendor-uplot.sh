#!/usr/bin/env bash
# Refreshes the plotting library that hpsf sweep's HTML report embeds (tools/hpsf/report_assets/vendor/): uPlot
# from the npm registry, at the pinned version, checked against the tarball's SHA-256. The files are committed, so a
# build needs neither npm nor the network; run this only to change the version (and update both pins).
set -euo pipefail
version=1.6.32
sha256=4b8a8191e425658e3ea8c8c1314b0fc679c861ee3a1af2b20c7b16ba50b5133d
vendor="$(cd "$(dirname "$0")/.." && pwd)/tools/hpsf/report_assets/vendor"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
npm pack "uplot@${version}" --silent > /dev/null
echo "${sha256}  uplot-${version}.tgz" | sha256sum --check --quiet
tar xzf "uplot-${version}.tgz"
cp package/dist/uPlot.iife.min.js package/dist/uPlot.min.css "$vendor/"
cp package/LICENSE "$vendor/uPlot-LICENSE"
echo "uPlot ${version} in ${vendor}"
