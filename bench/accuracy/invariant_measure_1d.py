#!/usr/bin/python3
"""Invariant-measure error of one-step Brownian dynamics schemes, computed exactly (no sampling) on a
circle: the Markov chain's transition kernel on a fine grid (Gauss-Hermite quadrature of the noise,
linear deposit), its stationary vector, and the L1 distance from the Boltzmann density exp(-U).

    dX = (M F + M') dt + sqrt(2 M) dW,   F = -U',  U = 2 cos x + 0.5 sin 2x,  kT = 1

Schemes of one or two mobility products a step: Euler-Maruyama with the exact drift; the drift taken at
x + sqrt(h M / 2) xi (Leimkuhler-Matthews's chain); fldsim's Euler-Maruyama with the midpoint thermal
drift (the FLD default, framework/src/dynamics/TimeIntegrator.cpp); the same with the Brownian half step
alone as predictor. Each is also observed at the post-processed point x + sqrt(h M(x) / 2) xi (what
`leimkuhler_matthews` samples for a constant M). With M constant the post-processed Leimkuhler-Matthews
chain is second order (the check that this harness sees second order); with a varying M none of them is
(docs/time_steps.md, "A second-order scheme for FLD's multiplicative noise?").

usage: invariant_measure_1d.py [GRID]      (default 800 points; a few minutes)
"""
import sys
import numpy as np

L = 2 * np.pi
G = int(sys.argv[1]) if len(sys.argv) > 1 else 800
xg = np.arange(G) * L / G
U = lambda x: 2 * np.cos(x) + 0.5 * np.sin(2 * x)
F = lambda x: 2 * np.sin(x) - np.cos(2 * x)  # -U'
xi, w = np.polynomial.hermite_e.hermegauss(120)
w = w / w.sum()
rho = np.exp(-U(xg))
rho /= rho.sum()


def mobility(amplitude):
    return (lambda x: 1 + amplitude * np.sin(x + 0.3)), (lambda x: amplitude * np.cos(x + 0.3))


def kernel(move):
    """Row i: the distribution of move(x_i, xi) deposited linearly on the periodic grid."""
    P = np.zeros((G, G))
    for i, x in enumerate(xg):
        y = np.mod(move(x, xi), L) / (L / G)
        j = np.floor(y).astype(int)
        f = y - j
        np.add.at(P[i], j % G, w * (1 - f))
        np.add.at(P[i], (j + 1) % G, w * f)
    return P


def stationary(P):
    vals, vecs = np.linalg.eig(P.T)
    p = np.real(vecs[:, np.argmin(abs(vals - 1))])
    return p / p.sum()


def schemes(M, dM):
    def drift(x):
        return M(x) * F(x) + dM(x)

    def euler(x, h, z):
        return x + h * drift(x) + np.sqrt(2 * h * M(x)) * z

    def drift_at_half_noise(x, h, z):  # Leimkuhler-Matthews's chain: the drift at x + sqrt(h M / 2) xi
        return x + h * drift(x + np.sqrt(0.5 * h * M(x)) * z) + np.sqrt(2 * h * M(x)) * z

    def midpoint(x, h, z):  # x* = x + h/2 M(x)(F(x) + F_B), x' = x + h M(x*)(F(x*) + F_B), F_B frozen
        FB = np.sqrt(2 / (h * M(x))) * z
        xs = x + 0.5 * h * M(x) * (F(x) + FB)
        return x + h * M(xs) * (F(xs) + FB)

    def brownian_midpoint(x, h, z):  # the same with the predictor's Brownian half step only
        FB = np.sqrt(2 / (h * M(x))) * z
        xs = x + 0.5 * h * M(x) * FB
        return x + h * M(xs) * (F(xs) + FB)

    return {"Euler-Maruyama, exact drift": euler,
            "drift at x + sqrt(h M/2) xi (LM's chain)": drift_at_half_noise,
            "midpoint drift (fldsim's default)": midpoint,
            "midpoint, Brownian predictor only": brownian_midpoint}


def main():
    print(f"grid {G} points; L1 = sum |p_h - rho| (0 for an exact scheme)")
    print("| mobility | scheme | h | L1 | L1 observed at x + sqrt(h M / 2) xi |")
    print("| --- | --- | --- | --- | --- |")
    for label, amplitude in [("constant", 0.0), ("1 + 0.6 sin(x + 0.3)", 0.6)]:
        M, dM = mobility(amplitude)
        for name, scheme in schemes(M, dM).items():
            for h in [0.08, 0.04, 0.02]:
                p = stationary(kernel(lambda x, z: scheme(x, h, z)))
                post = kernel(lambda x, z: x + np.sqrt(0.5 * h * M(x)) * z).T @ p
                print(f"| {label} | {name} | {h:g} | {abs(p - rho).sum():.2e} | {abs(post - rho).sum():.2e} |")


if __name__ == "__main__":
    main()
