"""Build the corner paper's MDP2 exactly as stopscan does and solve it with pymdptoolbox.

Same belief (0.5*N(30,3) + 0.5*N(90,3) degrees, truncated to [0, 180]), same costs
(D = 10 m, tau = 2 s, v = 0.5 m/s, no move time), same Bayes-correct transitions, same
self-loop. Prints one JSON line: the toolbox's time and its value of the start state, so it
can be compared with `stopscan corner policy --solver general --step-deg 90/n`.
"""
import argparse, json, math, sys, time

import numpy as np
import scipy.sparse as sp
import mdptoolbox.mdp


def cdf(theta):
    if theta <= 0: return 0.0
    if theta >= math.pi: return 1.0
    phi = lambda z: 0.5 * math.erfc(-z / math.sqrt(2))
    total = 0.0
    for w, m, s in [(0.5, 30.0, 3.0), (0.5, 90.0, 3.0)]:
        m, s = math.radians(m), math.radians(s)
        a, b = phi(-m / s), phi((math.pi - m) / s)
        total += w * min(max((phi((theta - m) / s) - a) / (b - a), 0.0), 1.0)
    return total


def build(n, dense):
    D, tau, v, mt = 10.0, 2.0, 0.5, 0.0
    phi = [min(i * (math.pi / 2) / n, math.pi / 2) for i in range(n + 1)]
    F = [cdf(p) for p in phi]
    step = [D * (phi[i + 1] - phi[i]) / v for i in range(n)]
    sid = lambda i, j: i * (i + 1) // 2 + j
    S = sid(n, n) + 2
    fin = S - 1
    rows = [[], []]; cols = [[], []]; vals = [[], []]
    R = np.zeros((S, 2))
    def add(a, s, t, p):
        rows[a].append(s); cols[a].append(t); vals[a].append(p)
    for i in range(n + 1):
        for j in range(i + 1):
            s = sid(i, j)
            if i == n:   # the corner: both actions scan and finish
                for a in (0, 1): add(a, s, fin, 1.0); R[s, a] = -tau
                continue
            add(0, s, sid(i + 1, j), 1.0); R[s, 0] = -(step[i] + (mt if j == i else 0.0))
            if j == i:   # the useless self-loop
                add(1, s, s, 1.0)
            else:
                miss = (1 - F[i]) / (1 - F[j]) if F[j] < 1 else 0.0
                add(1, s, fin, 1 - miss); add(1, s, sid(i, i), miss)
            R[s, 1] = -tau
    for a in (0, 1): add(a, fin, fin, 1.0)
    P = [sp.csr_matrix((vals[a], (rows[a], cols[a])), shape=(S, S)) for a in (0, 1)]
    if dense:
        P = np.array([m.toarray() for m in P])
    return P, R, sid(0, 0), S


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=180)
    ap.add_argument("--dense", action="store_true")
    a = ap.parse_args()
    t0 = time.perf_counter()
    try:
        P, R, start, S = build(a.n, a.dense)
    except MemoryError as e:
        print(json.dumps({"peer": "pymdptoolbox", "n": a.n, "dense": a.dense, "error": f"MemoryError: {e}"}))
        return
    t1 = time.perf_counter()
    # Undiscounted in the model; the toolbox's iterative evaluation stops when a sweep changes
    # less than (1 - g)/g * eps, which is never for g = 1, so use g = 1 - 1e-9 (values change
    # by ~1e-9 relative).
    pi = mdptoolbox.mdp.PolicyIteration(P, R, 1 - 1e-9, eval_type=1, max_iter=1000)
    pi.run()
    t2 = time.perf_counter()
    print(json.dumps({"peer": "pymdptoolbox", "n": a.n, "states": S, "dense": a.dense,
                      "build_seconds": t1 - t0, "solve_seconds": t2 - t1,
                      "iterations": pi.iter, "start_value": -pi.V[start]}))


if __name__ == "__main__":
    main()
