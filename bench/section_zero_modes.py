#!/usr/bin/env python3
"""Issue 50: zero-energy modes of the CUF element (Lagrange section x Lagrange axis, one 3D
tensor-product solid) with the section's full ((p+1)^2) or reduced (p^2) Gauss rule, the axis
always full: the null space of the stiffness of one element and of a patch of section elements
sharing nodes (free, no supports). Pure Python (Gaussian elimination with full pivoting: the rank).

  python3 bench/section_zero_modes.py [modes]   # zero modes of one element and of a patch
  python3 bench/section_zero_modes.py bending    # plate bending across a wall, full/reduced/selective
A count above 6 (rigid motions) is a spurious mode; a patch count that grows with the patch means
the mode is communicable across elements."""
import math


def gauss(n):
    # Gauss-Legendre points and weights by Newton on P_n
    pts, wts = [], []
    for i in range(n):
        x = math.cos(math.pi * (i + 0.75) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            if n == 1:
                p0, p1 = 1.0, x
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-15:
                break
        pts.append(x)
        wts.append(2 / ((1 - x * x) * dp * dp))
    return pts, wts


def lagrange(p, x):
    nodes = [-1 + 2 * i / p for i in range(p + 1)]
    n, d = [], []
    for i, xi in enumerate(nodes):
        v = 1.0
        for j, xj in enumerate(nodes):
            if j != i:
                v *= (x - xj) / (xi - xj)
        s = 0.0
        for k, xk in enumerate(nodes):
            if k == i:
                continue
            t = 1 / (xi - xk)
            for j, xj in enumerate(nodes):
                if j != i and j != k:
                    t *= (x - xj) / (xi - xj)
            s += t
        n.append(v)
        d.append(s)
    return n, d


def stiffness(ps, pa, nsx, a, t, length, rs, ra, e=200e9, nu=0.3, rows=range(6)):
    """A patch of nsx section elements (each a x t, order ps) along x, one through z, one axis
    element (order pa, length): the assembled stiffness, section rule rs x rs, axis rule ra."""
    lam, mu = e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))
    nxn, nzn, nyn = nsx * ps + 1, ps + 1, pa + 1
    ndof = 3 * nxn * nzn * nyn
    k = [[0.0] * ndof for _ in range(ndof)]
    gs, ws = gauss(rs)
    ga, wa = gauss(ra)
    for el in range(nsx):
        dofs = []
        for iy in range(nyn):
            for iz in range(nzn):
                for ix in range(ps + 1):
                    node = (iy * nzn + iz) * nxn + el * ps + ix
                    dofs += [3 * node, 3 * node + 1, 3 * node + 2]
        for xi, wx in zip(gs, ws):
            for eta, wz in zip(gs, ws):
                for zeta, wy in zip(ga, wa):
                    nx_, dx_ = lagrange(ps, xi)
                    nz_, dz_ = lagrange(ps, eta)
                    ny_, dy_ = lagrange(pa, zeta)
                    grads = []
                    for iy in range(nyn):
                        for iz in range(nzn):
                            for ix in range(ps + 1):
                                grads.append((dx_[ix] * nz_[iz] * ny_[iy] * 2 / a,
                                              ny_[iy] * nx_[ix] * dy_[iy] * 0 + nx_[ix] * nz_[iz] * dy_[iy] * 2 / length,
                                              nx_[ix] * dz_[iz] * ny_[iy] * 2 / t))
                    w = wx * wz * wy * (a / 2) * (t / 2) * (length / 2)
                    # B rows: xx, yy, zz, xy, xz, yz
                    b = [[0.0] * len(dofs) for _ in range(6)]
                    for m, (gx, gy, gz) in enumerate(grads):
                        b[0][3 * m] = gx
                        b[1][3 * m + 1] = gy
                        b[2][3 * m + 2] = gz
                        b[3][3 * m], b[3][3 * m + 1] = gy, gx
                        b[4][3 * m], b[4][3 * m + 2] = gz, gx
                        b[5][3 * m + 1], b[5][3 * m + 2] = gz, gy
                    db = [[(lam + 2 * mu) * b[0][j] + lam * (b[1][j] + b[2][j]) for j in range(len(dofs))],
                          [(lam + 2 * mu) * b[1][j] + lam * (b[0][j] + b[2][j]) for j in range(len(dofs))],
                          [(lam + 2 * mu) * b[2][j] + lam * (b[0][j] + b[1][j]) for j in range(len(dofs))],
                          [mu * b[3][j] for j in range(len(dofs))],
                          [mu * b[4][j] for j in range(len(dofs))],
                          [mu * b[5][j] for j in range(len(dofs))]]
                    for r in rows:
                        br, dbr = b[r], db[r]
                        nzr = [j for j in range(len(dofs)) if br[j] != 0.0]
                        for i in nzr:
                            bi = br[i] * w
                            ki = k[dofs[i]]
                            for j in range(len(dofs)):
                                if dbr[j] != 0.0:
                                    ki[dofs[j]] += bi * dbr[j]
    return k


def nullity(k, rel=1e-10):
    a = [row[:] for row in k]
    n = len(a)
    scale = max(abs(a[i][i]) for i in range(n))
    rank = 0
    rows, cols = list(range(n)), list(range(n))
    for step in range(n):
        best, bi, bj = 0.0, -1, -1
        for i in range(step, n):
            ri = a[i]
            for j in range(step, n):
                if abs(ri[j]) > best:
                    best, bi, bj = abs(ri[j]), i, j
        if best <= rel * scale:
            break
        a[step], a[bi] = a[bi], a[step]
        for r in a:
            r[step], r[bj] = r[bj], r[step]
        piv = a[step][step]
        for i in range(step + 1, n):
            f = a[i][step] / piv
            if f != 0.0:
                ri, rs = a[i], a[step]
                for j in range(step, n):
                    ri[j] -= f * rs[j]
        rank += 1
    return n - rank


def zero_modes():
    a, t, length = 0.025, 0.003, 1.0 / 12
    print("section | axis | section elements in patch | section rule | DOF | zero modes | spurious (beyond 6)")
    for ps, pa, name, an in ((2, 1, "L9", "B2"), (2, 3, "L9", "B4"), (3, 3, "L16", "B4")):
        for nsx in (1, 3):
            for rs in (ps + 1, ps):
                k = stiffness(ps, pa, nsx, a, t, length, rs, pa + 1)
                z = nullity(k)
                print(f"{name} | {an} | {nsx} | {rs}x{rs} | {len(k)} | {z} | {z - 6}", flush=True)
            # selective: the in-section shear (xz) with p x p, everything else full
            k = stiffness(ps, pa, nsx, a, t, length, ps + 1, pa + 1, rows=(0, 1, 2, 3, 5))
            kr = stiffness(ps, pa, nsx, a, t, length, ps, pa + 1, rows=(4,))
            k = [[x + y for x, y in zip(r1, r2)] for r1, r2 in zip(k, kr)]
            z = nullity(k)
            print(f"{name} | {an} | {nsx} | selective (xz shear {ps}x{ps}) | {len(k)} | {z} | {z - 6}", flush=True)


def solve(k, f, fixed):
    """Solve K u = f with the listed DOFs zero (dense Gaussian elimination)."""
    free = [i for i in range(len(k)) if i not in fixed]
    a = [[k[i][j] for j in free] + [f[i]] for i in free]
    n = len(free)
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        for r in range(c + 1, n):
            m = a[r][c] / a[c][c]
            if m:
                for j in range(c, n + 1):
                    a[r][j] -= m * a[c][j]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (a[r][n] - sum(a[r][j] * x[j] for j in range(r + 1, n))) / a[r][r]
    u = [0.0] * len(k)
    for i, v in zip(free, x):
        u[i] = v
    return u


def cylindrical_bending(ps, nsx, mode, b=0.1, t=0.003, e=200e9, nu=0.3, q=100.0):
    """Plate bending across a wall, plane strain: the 3D element (section order ps, nsx along x,
    one through z; one B2 axis element of length 1, u_y = 0 everywhere), edge x = 0 clamped, a line
    load q (N/m) along -z on the edge x = b. Returns w at x = b, mid-thickness."""
    a, length = b / nsx, 1.0
    if mode == "full":
        k = stiffness(ps, 1, nsx, a, t, length, ps + 1, 2, e, nu)
    elif mode == "reduced":
        k = stiffness(ps, 1, nsx, a, t, length, ps, 2, e, nu)
    else:
        k = stiffness(ps, 1, nsx, a, t, length, ps + 1, 2, e, nu, rows=(0, 1, 2, 3, 5))
        kr = stiffness(ps, 1, nsx, a, t, length, ps, 2, e, nu, rows=(4,))
        k = [[x + y for x, y in zip(r1, r2)] for r1, r2 in zip(k, kr)]
    nxn, nzn = nsx * ps + 1, ps + 1
    fixed, f = set(), [0.0] * len(k)
    wz = {1: [0.5, 0.5], 2: [1 / 6, 4 / 6, 1 / 6], 3: [1 / 8, 3 / 8, 3 / 8, 1 / 8]}[ps]
    for iy in range(2):
        for iz in range(nzn):
            for ix in range(nxn):
                node = (iy * nzn + iz) * nxn + ix
                fixed.add(3 * node + 1)
                if ix == 0:
                    fixed |= {3 * node, 3 * node + 2}
                if ix == nxn - 1:
                    f[3 * node + 2] -= q * length * 0.5 * wz[iz]
    u = solve(k, f, fixed)
    mid = (0 * nzn + ps // 2) * nxn + nxn - 1
    if ps % 2:  # no mid node: average the two nearest
        return -(u[3 * ((ps // 2) * nxn + nxn - 1) + 2] + u[3 * ((ps // 2 + 1) * nxn + nxn - 1) + 2]) / 2
    return -u[3 * mid + 2]


def bending_table():
    e, nu, b, t, q = 200e9, 0.3, 0.1, 0.003, 100.0
    d = e * t**3 / (12 * (1 - nu**2))
    g = e / (2 * (1 + nu))
    theory = q * b**3 / (3 * d) + q * b / (5 / 6 * g * t)  # plane-strain Timoshenko cantilever
    print(f"cylindrical bending, theory (plane-strain Timoshenko) w = {theory:.6g} m")
    print("section | along x | aspect | full err % | reduced err % | selective (xz shear) err %")
    for ps, name in ((2, "L9"), (3, "L16")):
        for nsx in (1, 2, 4, 8):
            errs = [100 * (cylindrical_bending(ps, nsx, m) - theory) / theory for m in ("full", "reduced", "selective")]
            print(f"{name} | {nsx} | {b / nsx / t:.1f} | " + " | ".join(f"{x:+.2f}" for x in errs), flush=True)


if __name__ == "__main__":
    import sys
    {"modes": zero_modes, "bending": bending_table}[sys.argv[1] if len(sys.argv) > 1 else "modes"]()
