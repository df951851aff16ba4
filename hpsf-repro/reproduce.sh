#!/bin/sh
# Reproduces the failed cross-check exactly (same records, options, seed and schedule) from any folder on any
# machine with hpsf: $HPSF if set, else hpsf on PATH. Writes reproduced.json beside report.json.
cd "$(dirname "$0")" || exit 3
hpsf=${HPSF:-$(command -v hpsf)}
if [ -z "$hpsf" ]; then echo "reproduce.sh: no hpsf: set HPSF=/path/to/hpsf or put hpsf on PATH" >&2; exit 3; fi
written='hpsf 0.1.0'
running=$("$hpsf" --version 2>/dev/null)
[ "$running" = "$written" ] || echo "reproduce.sh: warning: written by $written, reproduced with ${running:-an hpsf that gives no version} ($hpsf)" >&2
exec "$hpsf" crosscheck records.hpsfv '--backends' 'reference,vulkan' '--normal' 'none' '--normal-in-fingerprint-only' 'false' '--seed' '1456416002' '--capacity' '32' '--probe-limit' '32' '--fingerprint-bits' '8' '--level-change' 'seed:1' --repro-dir reproduced --json > reproduced.json
