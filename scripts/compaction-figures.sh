#!/bin/bash
# The per-slot passes' time with and without --compaction occupied-list (docs/results.md, "Compaction"): the animated
# Cornell box at 1080p, 1 spp, 16 frames, 2^22 slots, stale:4 eviction and an ema blend, on the emulator and Vulkan,
# ROUNDS times each, the two modes alternating so that both see the same machine. Prints the medians over frames 4 to 15
# (where every pass runs) of each run. Usage: scripts/compaction-figures.sh [HPSF] [ROUNDS]
set -euo pipefail
hpsf=${1:-build/default/bin/hpsf}
rounds=${2:-2}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scene=$(dirname "$0")/../scenes/cornell-animated.json
for round in $(seq 1 "$rounds"); do
  for backend in emulated vulkan; do
    for compaction in none occupied-list; do
      "$hpsf" render "$scene" --size 1920x1080 --spp 1 --frames 16 --eviction stale:4 --temporal ema:0.2 \
        --backend "$backend" --compaction "$compaction" --json -o "$out/image.exr" >"$out/$backend-$compaction-$round.json"
    done
  done
done
python3 - "$out" <<'PY'
import glob, json, os, statistics, sys
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    frames = json.load(open(path))["frames"][4:]
    ms = lambda f, k, s: f.get(k, {}).get(s, 0.0) * 1e3
    evict = statistics.median(ms(f, "eviction", "eviction_s") for f in frames)
    blend = statistics.median(ms(f, "temporal", "temporal_s") for f in frames)
    gather = statistics.median(ms(f, "compaction", "compaction_s") for f in frames)
    total = statistics.median(ms(f, "eviction", "eviction_s") + ms(f, "temporal", "temporal_s") +
                              ms(f, "compaction", "compaction_s") for f in frames)
    occupied = [f["compaction"]["occupied"] for f in frames if "compaction" in f]
    print(f"{os.path.basename(path)[:-5]:28s} evict+reclaim(+prune) {evict:7.1f} ms  blend {blend:7.1f} ms  "
          f"gather {gather:6.1f} ms  per-slot passes {total:7.1f} ms" +
          (f"  occupied {min(occupied)} to {max(occupied)}" if occupied else ""))
PY
