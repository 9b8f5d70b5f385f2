#!/usr/bin/python3
"""Prints docs/extremes.md's table of the status battery: small QPs whose answers are known by hand
(tests/cross_backend/test_status_certificate.cpp and test_free_modes.cpp hold the same cases and
their assertions), status and relative KKT residual per backend at tol 1e-8.

    PYTHONPATH=build/python /usr/bin/python3 tools/status_battery.py [--null-space]

--null-space passes each floating QP's null space to QuadraticProgram (otherwise solve() finds it
itself after a first run that the certificate rejects)."""
import argparse

import numpy as np

import contactqp


def chain(springs, ground=0.0):
    n = len(springs) + 1
    K = np.zeros((n, n))
    for i, k in enumerate(springs):
        K[i, i] += k
        K[i + 1, i + 1] += k
        K[i, i + 1] -= k
        K[i + 1, i] -= k
    K[0, 0] += ground
    return K


def wall(n, j, side):
    row = np.zeros(n)
    row[j] = side
    return row


def battery():
    """(name, K, f, B, g, null space or None)."""
    one = np.ones((3, 1))
    two_walls = np.array([wall(3, 0, -1), wall(3, 2, 1)])
    sideways = np.zeros((4, 4))
    sideways[0, 0] = sideways[2, 2] = 1
    sideways[0, 2] = sideways[2, 0] = -1
    sideways_modes = np.zeros((4, 3))
    sideways_modes[[0, 2], 0] = 1
    sideways_modes[1, 1] = sideways_modes[3, 2] = 1
    return [
        ("chain pushed against a wall", chain([1, 2]), [1, 0, 0], two_walls, [2, 0.5], one),
        ("chain pulled away", chain([1, 2]), [-1, 0, 0], [wall(3, 2, 1)], [0.5], one),
        ("chain pulled apart, two walls", chain([1, 2]), [-1, 0, 1], two_walls, [0.25, 0.25], one),
        ("free point in a corner", np.zeros((2, 2)), [-1, -2], -np.eye(2), [0, 0], np.eye(2)),
        ("free point along its wall", np.zeros((2, 2)), [-1, 1], [[-1, 0]], [0], np.eye(2)),
        ("two masses free sideways", sideways, [1, 0, 0, 0], [wall(4, 2, 1)], [0.5], sideways_modes),
        ("contradictory rows", chain([1], 1), [0.3, 0], [[1, 0], [-1, 0]], [-1, -1], None),
        ("stiffness contrast 1e4", chain([1e4, 1], 1), [0, 0, 1e4], [wall(3, 2, 1)], [0.5], None),
        ("grounded by 1e-12, pulled away", chain([1, 1], 1e-12), [-1, 0, 0], [wall(3, 2, 1)], [0.5], None),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--null-space", action="store_true", help="give each floating QP its null space")
    args = parser.parse_args()
    backends = contactqp.available_backends()
    print("| case | " + " | ".join(b.label for b in backends) + " |")
    print("|---|" + "---|" * len(backends))
    for name, K, f, B, g, modes in battery():
        given = modes if args.null_space else None
        qp = contactqp.QuadraticProgram(np.asarray(K, float), np.asarray(f, float), np.asarray(B, float),
                                        np.asarray(g, float), null_space=given)
        cells = []
        for backend in backends:
            s = contactqp.solve(qp, backend=backend, tol=1e-8)
            cells.append(f"{s.status.label} ({s.certificate.kkt_max:.0e})")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
