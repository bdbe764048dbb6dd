"""Master segment geometry and the independent truth for the local search study.

Everything here is numpy only and shares no code with the C++ library, so that it
can judge it. The problem (docs/local-search.md, seed paper eq. 1-7): minimise
f(xi) = |ys - y(xi)|^2 with y(xi) = sum_i N_i(xi) Y_i over a quad4 or quad8 segment.

Shape functions are built from their monomial basis by inverting the Vandermonde
matrix at the nodes, so their derivatives of any order are exact polynomials:
  quad4: {1, xi1, xi2, xi1 xi2}
  quad8: {1, xi1, xi2, xi1^2, xi1 xi2, xi2^2, xi1^2 xi2, xi1 xi2^2}  (serendipity)
Node order: corners (-1,-1) (1,-1) (1,1) (-1,1), then mid-sides (0,-1) (1,0) (0,1) (-1,0).
"""

import numpy as np

NODE_XI = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], dtype=float)

# Exponents (p, q) of the monomials xi1^p xi2^q.
_MONOMIALS = {
    4: [(0, 0), (1, 0), (0, 1), (1, 1)],
    8: [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2), (2, 1), (1, 2)],
}


def _coefficients(n_nodes):
    """C such that N(xi) = monomials(xi) @ C, shape (n_monomials, n_nodes)."""
    exps = _MONOMIALS[n_nodes]
    vander = np.array([[x ** p * y ** q for (p, q) in exps] for x, y in NODE_XI[:n_nodes]])
    return np.linalg.inv(vander)  # V C = I: rows monomials, columns nodes


_COEFF = {n: _coefficients(n) for n in (4, 8)}


def _monomial_derivative(xi1, xi2, p, q, d1, d2):
    """d^(d1+d2)/dxi1^d1 dxi2^d2 of xi1^p xi2^q, elementwise."""
    if d1 > p or d2 > q:
        return np.zeros(np.broadcast(xi1, xi2).shape)
    c = 1.0
    for k in range(d1):
        c *= p - k
    for k in range(d2):
        c *= q - k
    return c * xi1 ** (p - d1) * xi2 ** (q - d2)


def shape(n_nodes, xi1, xi2, d1=0, d2=0):
    """Derivative (d1, d2) of the shape functions at points xi: shape (..., n_nodes)."""
    xi1 = np.asarray(xi1, dtype=float)
    xi2 = np.asarray(xi2, dtype=float)
    mono = np.stack([_monomial_derivative(xi1, xi2, p, q, d1, d2) for (p, q) in _MONOMIALS[n_nodes]], axis=-1)
    return mono @ _COEFF[n_nodes]


def evaluate(nodes, point, xi):
    """f, gradient and Hessian of f = |ys - y(xi)|^2 for a batch.

    nodes (B, n, 3), point (B, 3), xi (B, 2) -> f (B,), g (B, 2), H (B, 2, 2), r (B, 3).
    g_a = -2 r.a_a, H_ab = 2 (a_a.a_b - r.y_,ab) with r = ys - y, a_a = y_,a.
    """
    n = nodes.shape[1]
    x1, x2 = xi[:, 0], xi[:, 1]
    y = np.einsum("bn,bnk->bk", shape(n, x1, x2), nodes)
    a1 = np.einsum("bn,bnk->bk", shape(n, x1, x2, 1, 0), nodes)
    a2 = np.einsum("bn,bnk->bk", shape(n, x1, x2, 0, 1), nodes)
    y11 = np.einsum("bn,bnk->bk", shape(n, x1, x2, 2, 0), nodes)
    y12 = np.einsum("bn,bnk->bk", shape(n, x1, x2, 1, 1), nodes)
    y22 = np.einsum("bn,bnk->bk", shape(n, x1, x2, 0, 2), nodes)
    r = point - y
    f = np.einsum("bk,bk->b", r, r)
    g = np.stack([-2 * np.einsum("bk,bk->b", r, a1), -2 * np.einsum("bk,bk->b", r, a2)], axis=-1)
    h11 = 2 * (np.einsum("bk,bk->b", a1, a1) - np.einsum("bk,bk->b", r, y11))
    h12 = 2 * (np.einsum("bk,bk->b", a1, a2) - np.einsum("bk,bk->b", r, y12))
    h22 = 2 * (np.einsum("bk,bk->b", a2, a2) - np.einsum("bk,bk->b", r, y22))
    H = np.stack([np.stack([h11, h12], -1), np.stack([h12, h22], -1)], -2)
    return f, g, H, r


def position(nodes, xi):
    """y(xi) for a batch: nodes (B, n, 3), xi (B, 2) -> (B, 3)."""
    return np.einsum("bn,bnk->bk", shape(nodes.shape[1], xi[:, 0], xi[:, 1]), nodes)


def tangents(nodes, xi):
    n = nodes.shape[1]
    a1 = np.einsum("bn,bnk->bk", shape(n, xi[:, 0], xi[:, 1], 1, 0), nodes)
    a2 = np.einsum("bn,bnk->bk", shape(n, xi[:, 0], xi[:, 1], 0, 1), nodes)
    return a1, a2


def unit_normal(nodes, xi):
    a1, a2 = tangents(nodes, xi)
    nrm = np.cross(a1, a2)
    return nrm / np.linalg.norm(nrm, axis=-1, keepdims=True)


def stationary_kind(H, tol=1e-12):
    """'minimum', 'saddle' or 'maximum' from the eigenvalues of 2x2 Hessians (B, 2, 2)."""
    ev = np.linalg.eigvalsh(H)
    scale = np.maximum(np.abs(ev).max(axis=-1), 1e-300)
    lo, hi = ev[:, 0] / scale, ev[:, 1] / scale
    kind = np.full(len(H), "degenerate", dtype=object)
    kind[(lo > tol)] = "minimum"
    kind[(lo < -tol) & (hi > tol)] = "saddle"
    kind[(hi < -tol)] = "maximum"
    return kind


# ---------------------------------------------------------------------------
# Truth: the closest point of the segment itself (xi in [-1,1]^2).


def _grid_local_minima(f):
    """Mask of discrete local minima (8-neighbourhood, boundaries included) of f (B, G, G)."""
    m = f.copy()  # 3x3 minimum filter, separable: along axis 1, then axis 2
    np.minimum(m[:, 1:], f[:, :-1], out=m[:, 1:])
    np.minimum(m[:, :-1], f[:, 1:], out=m[:, :-1])
    m2 = m.copy()
    np.minimum(m2[:, :, 1:], m[:, :, :-1], out=m2[:, :, 1:])
    np.minimum(m2[:, :, :-1], m[:, :, 1:], out=m2[:, :, :-1])
    return f <= m2


def refine_constrained(nodes, point, xi, iterations=40):
    """Projected Newton with an active set on the bounds |xi_a| <= 1, batched.

    A bound is active when xi sits on it and the gradient pushes outward; on the free
    coordinates the step solves the Hessian (shifted to be positive definite when it is
    not), then a backtracking line search on the projection onto the box keeps f from
    rising (beyond round-off, so that the last Newton steps can polish xi).
    Returns xi (B, 2), f (B,), projected-gradient norm (B,).
    """
    xi = np.clip(np.array(xi, dtype=float), -1.0, 1.0)
    B = len(xi)
    work = np.arange(B)  # candidates still moving
    for _ in range(iterations):
        if len(work) == 0:
            break
        x, nd, pt = xi[work], nodes[work], point[work]
        f, g, H, _ = evaluate(nd, pt, x)
        active = ((x >= 1.0) & (g < 0)) | ((x <= -1.0) & (g > 0))
        free = ~active
        Hr = H.copy()  # reduced Hessian: identity on the active coordinates
        for a in range(2):
            Hr[active[:, a], a, :] = 0.0
            Hr[active[:, a], :, a] = 0.0
            Hr[active[:, a], a, a] = 1.0
        gr = np.where(free, g, 0.0)
        ev = np.linalg.eigvalsh(Hr)
        scale = np.maximum(np.abs(ev).max(axis=-1), 1e-30)
        shift = np.where(ev[:, 0] < 1e-8 * scale, 1e-8 * scale - ev[:, 0] + 1e-3 * scale, 0.0)
        step = -np.linalg.solve(Hr + shift[:, None, None] * np.eye(2), gr[..., None])[..., 0]
        step = np.where(free, step, 0.0)
        alpha = np.ones(len(work))
        accepted = np.zeros(len(work), dtype=bool)
        x_new = x.copy()
        allowed = f * (1.0 + 1e-13) + 1e-300
        for _ls in range(40):
            trial = np.clip(x + alpha[:, None] * step, -1.0, 1.0)
            ft = evaluate(nd, pt, trial)[0]
            ok = (ft <= allowed) & ~accepted
            x_new[ok] = trial[ok]
            accepted |= ok
            if accepted.all():
                break
            alpha = np.where(accepted, alpha, alpha * 0.5)
        moved = np.linalg.norm(x_new - x, axis=-1)
        xi[work] = x_new
        work = work[moved > 1e-15]
    f, g, H, _ = evaluate(nodes, point, xi)
    pg = np.where(((xi >= 1.0) & (g < 0)) | ((xi <= -1.0) & (g > 0)), 0.0, g)
    return xi, f, np.linalg.norm(pg, axis=-1)


def closest_point(nodes, point, grid=201, candidates=4, chunk=64):
    """The closest point of each segment to its slave point, over [-1,1]^2.

    Dense grid of f, then the `candidates` lowest discrete local minima refined by
    refine_constrained; the best refined one wins. Returns dict of arrays:
    xi (B, 2), distance (B,), interior (B,) bool, gradnorm (B,).
    """
    nodes = np.asarray(nodes, dtype=float)
    point = np.asarray(point, dtype=float)
    B, n, _ = nodes.shape
    s = np.linspace(-1.0, 1.0, grid)
    X1, X2 = np.meshgrid(s, s, indexing="ij")
    N = shape(n, X1.ravel(), X2.ravel())  # (G*G, n)
    starts = np.empty((B, candidates, 2))
    for c0 in range(0, B, chunk):
        sl = slice(c0, min(B, c0 + chunk))
        b = sl.stop - sl.start
        f = np.zeros((grid * grid, b))
        for k in range(3):
            f += (N @ nodes[sl, :, k].T - point[sl, k]) ** 2
        f = np.ascontiguousarray(f.T).reshape(b, grid, grid)
        fm = np.where(_grid_local_minima(f), f, np.inf).reshape(b, -1)
        order = np.argpartition(fm, candidates, axis=1)[:, :candidates]
        # Fewer local minima than candidates: repeat the best one.
        finite = np.isfinite(np.take_along_axis(fm, order, axis=1))
        order = np.where(finite, order, order[:, :1])
        starts[sl, :, 0] = X1.ravel()[order]
        starts[sl, :, 1] = X2.ravel()[order]
    rep_nodes = np.repeat(nodes, candidates, axis=0)
    rep_point = np.repeat(point, candidates, axis=0)
    xi, f, gn = refine_constrained(rep_nodes, rep_point, starts.reshape(-1, 2))
    xi = xi.reshape(B, candidates, 2)
    f = f.reshape(B, candidates)
    gn = gn.reshape(B, candidates)
    best = np.argmin(f, axis=1)
    idx = np.arange(B)
    xi_best = xi[idx, best]
    return {
        "xi": xi_best,
        "distance": np.sqrt(np.maximum(f[idx, best], 0.0)),
        "interior": np.all(np.abs(xi_best) < 1.0 - 1e-9, axis=1),
        "gradnorm": gn[idx, best],
    }


def newton_unconstrained(nodes, point, xi, iterations=100):
    """Plain Newton on grad f = 0 (finds any stationary point), batched; for checks."""
    xi = np.array(xi, dtype=float)
    with np.errstate(all="ignore"):  # runs from far away may diverge; they are dropped
        return _newton_unconstrained(nodes, point, xi, iterations)


def _newton_unconstrained(nodes, point, xi, iterations):
    for _ in range(iterations):
        _, g, H, _ = evaluate(nodes, point, xi)
        det = H[:, 0, 0] * H[:, 1, 1] - H[:, 0, 1] ** 2
        ok = (np.abs(det) > 1e-300) & np.isfinite(det)
        step = np.zeros_like(xi)
        step[ok] = -np.linalg.solve(H[ok], g[ok][..., None])[..., 0]
        xi = xi + step
    f, g, H, _ = evaluate(nodes, point, xi)
    return xi, np.sqrt(f), np.linalg.norm(g, axis=-1), stationary_kind(H)
