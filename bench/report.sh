#!/usr/bin/env bash
# report.html's figures on this machine: its size, and how long after navigation headless
# Chromium draws its first frame (the page records performance.now() on <body> as
# data-first-frame-ms once the first step is drawn), over REPEAT fresh browser starts.
# Usage: bench/report.sh [REPEAT] [stopscan args...]   (default: 10, the main job's office run)
# Prints one JSON object. Needs Chromium (Debian: apt-get install chromium); not part of CI.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeat=${1:-10}
shift || true
browser=${STOPSCAN_CHROMIUM:-$(command -v chromium || command -v chromium-browser || command -v google-chrome)}
(cd "$root" && cargo build -q --release -p stopscan-cli)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "$#" -eq 0 ]; then
  "$root/target/release/stopscan" --out "$work/out" >/dev/null
  report="$work/out/report.html"
else
  "$root/target/release/stopscan" "$@" --report "$work/report.html" --out "$work/run.json" >/dev/null
  report="$work/report.html"
fi
times=()
for _ in $(seq "$repeat"); do
  ms=$("$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --host-resolver-rules='MAP * ~NOTFOUND' --user-data-dir="$work/profile" \
    --dump-dom "file://$report" 2>/dev/null | grep -o 'data-first-frame-ms="[0-9.]*"' | grep -o '[0-9.]*')
  times+=("$ms")
  rm -rf "$work/profile"
done
python3 - "$(stat -c %s "$report")" "${times[@]}" <<'PY'
import json, statistics, sys
size, times = int(sys.argv[1]), [float(t) for t in sys.argv[2:]]
print(json.dumps({"report_bytes": size, "first_frame_ms": times,
                  "first_frame_ms_median": statistics.median(times), "first_frame_ms_max": max(times)}))
PY
