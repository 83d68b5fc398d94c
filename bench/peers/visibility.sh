#!/usr/bin/env bash
# Side by side on this machine: stopscan's visibility against CGAL's triangular expansion
# (exact kernel) on every input of shared/bench/visibility, then every query's area compared.
# Usage: bench/peers/visibility.sh [SHARED_DIR]. Installs libcgal-dev if needed; not part of CI.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
shared=${1:-$root/../shared}
bench="$shared/bench/visibility"
(cd "$root" && cargo build -q --release -p stopscan-cli)
bin="$root/target/release/stopscan"
tmp=$(mktemp -d)
for e in env_100 env_1k env_10k env_100k; do
  f="$bench/$e.txt"
  echo "== $e =="
  "$bin" bench visibility --env "$f" --repeat 5
  bash "$bench/peer-cgal.sh" "$f" 3 5
  # Areas: CGAL's driver writes them; ours come from --queries.
  /tmp/stopscan-peer/vis_cgal "$f" tev epeck 1 5 "$tmp/$e.cgal" > /dev/null
  awk '/^QUERIES/{q=1; next} q' "$f" > "$tmp/$e.q"
  "$bin" visibility --env "$f" --queries "$tmp/$e.q" > "$tmp/$e.ours"
  python3 - "$tmp/$e.cgal" "$tmp/$e.ours" <<'PY'
import json, sys
cgal = [float(l) for l in open(sys.argv[1]) if l.strip()]
ours = [json.loads(l)["area"] for l in open(sys.argv[2]) if l.strip()]
assert len(cgal) == len(ours), (len(cgal), len(ours))
worst = max(abs(a - b) / max(abs(b), 1e-300) for a, b in zip(ours, cgal))
bad = sum(abs(a - b) > 1e-9 * abs(b) for a, b in zip(ours, cgal))
print(json.dumps({"compared": len(ours), "max_rel_diff": worst, "over_1e-9": bad}))
PY
done
