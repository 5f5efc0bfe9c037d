#!/usr/bin/python3
"""How much of the harder oval's slide along its edge can any registration recover? (docs/measurements/sicp.md, the oracle bound; summarised in docs/sicp.md, "Limits")

The generator's in-plane field (smooth_field in datasets/src/panel_shape.cpp, re-implemented here for the x and y
axes) is independent of its out-of-plane field, so a scan measures the in-plane motion only through the edge, and
there only across it: n . u along the edge's in-plane normal n. This script gives an estimator that component exactly
(no noise, all round the 380 x 260 mm oval, after the best rigid fit) and reports the mean row-by-row error of the
estimate against the rigid one: a bound for S-ICP, edge detection in the scan and smooth deformation fields alike.

Usage: /usr/bin/python3 docs/sicp_slide_bound.py   (numpy only; prints one line per seed)
"""
import numpy as np

MASK = (1 << 64) - 1


def field_hash(seed, index):
    z = (seed * 0x9E3779B97F4A7C15 + (index + 1) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    z ^= z >> 31
    return 2.0 * (z >> 11) / 9007199254740992.0 - 1.0


def in_plane_field(seed, points, field_mm=6.0, wavelength_mm=400.0):
    s = seed ^ 0x5EEDF1E1D
    d = np.zeros((len(points), 2))
    for axis in range(2):
        a = [field_hash(s, 10 * axis + j) for j in range(3)]
        total = sum(abs(x) for x in a)
        for j in range(3):
            key = 100 + 10 * axis + j
            direction = np.pi * field_hash(s, key)
            lam = wavelength_mm * (1.5 + 0.5 * field_hash(s, key + 1000))
            phase = np.pi * field_hash(s, key + 2000)
            u = np.cos(direction) * points[:, 0] + np.sin(direction) * points[:, 1]
            d[:, axis] += a[j] / total * np.sin(2 * np.pi * u / lam + phase)
    return field_mm * 0.5 * d


A, B, CENTRE = 190.0, 130.0, np.array([60.0, 30.0])  # harder_plate(): the 380 x 260 mm oval at (60, 30)
t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
P = CENTRE + np.c_[A * np.cos(t), B * np.sin(t)]
T = np.c_[-A * np.sin(t), B * np.cos(t)]
T /= np.linalg.norm(T, axis=1)[:, None]
N = np.c_[T[:, 1], -T[:, 0]]


def fit_across(basis, across, ridge=0.0):
    """The field in span(basis) whose across-edge component fits `across` (least squares, ridge)."""
    M = np.stack([(b * N).sum(1) for b in basis], 1)
    x = np.linalg.solve(M.T @ M + ridge * np.eye(M.shape[1]), M.T @ across)
    return sum(xi * b for xi, b in zip(x, basis))


def rigid_basis():
    q = P - CENTRE
    return [np.tile([1.0, 0.0], (len(P), 1)), np.tile([0.0, 1.0], (len(P), 1)), np.c_[-q[:, 1], q[:, 0]]]


def polynomial_basis(degree, scale=200.0):
    q = (P - CENTRE) / scale
    out = []
    for i in range(degree + 1):
        for j in range(degree + 1 - i):
            m = q[:, 0] ** i * q[:, 1] ** j
            out += [np.c_[m, 0 * m], np.c_[0 * m, m]]
    return out


def gaussian_process(across, length_mm, noise=1e-6):
    """Posterior mean of independent squared-exponential priors on u_x, u_y given n . u at the edge."""
    K = np.exp(-((P[:, None, :] - P[None, :, :]) ** 2).sum(-1) / (2 * length_mm ** 2))
    alpha = np.linalg.solve(K * (N @ N.T) + noise * np.eye(len(P)), across)
    return np.c_[K @ (alpha * N[:, 0]), K @ (alpha * N[:, 1])]


print("seed  rigid_mm  best_mm  change  (quadratic, cubic, GP 60/150/400 mm)")
for seed in [2, 3, 4, 21, 22, 23, 24, 25]:
    u = in_plane_field(seed, P)
    e = u - fit_across(rigid_basis(), (u * N).sum(1))  # what is left after the best rigid fit
    across = (e * N).sum(1)
    estimates = [fit_across(polynomial_basis(d), across, 1e-3) for d in (2, 3)]
    estimates += [1.5 * gaussian_process(across / 1.5, ell) for ell in (60.0, 150.0, 400.0)]
    rigid = np.linalg.norm(e, axis=1).mean()
    errors = [np.linalg.norm(e - f, axis=1).mean() for f in estimates]
    best = min(errors)
    print(f"{seed:4d}  {rigid:8.3f}  {best:7.3f}  {100 * (best / rigid - 1):+5.0f}%  " +
          " ".join(f"{x:.3f}" for x in errors))
