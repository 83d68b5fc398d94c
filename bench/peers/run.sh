#!/usr/bin/env bash
# Side by side, on this machine: stopscan's MDP2 solvers against pymdptoolbox on the same MDP.
# Usage: bench/peers/run.sh [N ...]   (default: 180 900). Needs PyPI; not part of CI.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
venv=${STOPSCAN_PEER_VENV:-${TMPDIR:-/tmp}/stopscan-peer-venv}
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q numpy scipy pymdptoolbox
(cd "$root" && cargo build -q --release -p stopscan-cli)
bin="$root/target/release/stopscan"
for n in "${@:-180 900}"; do
  for n1 in $n; do
    step=$(python3 -c "print(90/$n1)")
    echo "== n = $n1 stops =="
    "$bin" bench mdp --n "$n1" --repeat 5
    "$bin" bench mdp --solver general --n "$n1" --repeat 3
    "$bin" corner policy --belief 'mix:0.5*normal:30,3+0.5*normal:90,3' --step-deg "$step" --format json \
      | python3 -c 'import json,sys; v=json.load(sys.stdin); print(json.dumps({"stopscan_model_value": v["model_value"]}))'
    "$venv/bin/python" "$here/mdp2_pymdptoolbox.py" --n "$n1" || true
    if [ "$n1" -le 180 ]; then "$venv/bin/python" "$here/mdp2_pymdptoolbox.py" --n "$n1" --dense || true; fi
  done
done
