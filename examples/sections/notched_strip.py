#!/usr/bin/env python3
"""Writes examples/notched_strip_{coarse,medium,fine}.toml: a notched ply strip
pulled along its fibres, at three element sizes h around the crack path
(the crack-band check of docs/composites.md, "Ply damage").

Section in the x–z plane (x along the fibres and the pull, z across the
strip), one B2 element of depth t along y. The crack path is one column of
elements of width h centred on x = S + h/2, the notch the bottom rows of
that column left out (an element-wide slit from z = 0 to a). Beside the
column the elements grow by `GROWTH` towards the ends; along z every row is
h high. Run from the repository root:

    python3 examples/sections/notched_strip.py
"""

S = 2.0e-3  # length beside the crack column on each side (m)
W = 6.4e-3  # strip width along z (m)
A = 1.6e-3  # notch depth (m); the ligament is W - A = 4.8 mm
T = 1.0e-3  # depth along y (m)
GROWTH = 1.5
MESHES = {"coarse": 0.8e-3, "medium": 0.4e-3, "fine": 0.2e-3}


def side(h):
    """Element widths from the crack column outwards, filling S."""
    widths, total, w = [], 0.0, h
    while total + w < S - 1e-12:
        widths.append(w)
        total += w
        w *= GROWTH
    # the remainder joins the last element if it is short, else is one more
    rest = S - total
    if rest < 0.5 * widths[-1]:
        widths[-1] += rest
    else:
        widths.append(rest)
    return widths


def lines(h):
    """x lines and z lines of the grid."""
    w = side(h)
    left = [S - sum(w[:k]) for k in range(len(w) + 1)][::-1]
    right = [S + h + sum(w[:k]) for k in range(len(w) + 1)]
    x = left + right
    rows = round(W / h)
    z = [W * k / rows for k in range(rows + 1)]
    return x, z, len(w)


def mesh(h):
    x, z, n_side = lines(h)
    notch_rows = round(A / h)
    band = n_side  # index of the crack column among the x intervals
    index, points, quads = {}, [], []

    def point(i, k):
        if (i, k) not in index:
            index[(i, k)] = len(points)
            points.append((x[i], z[k]))
        return index[(i, k)]

    for k in range(len(z) - 1):
        for i in range(len(x) - 1):
            if i == band and k < notch_rows:
                continue
            # counter-clockwise in the x–z plane
            quads.append((point(i, k), point(i + 1, k), point(i + 1, k + 1), point(i, k + 1)))
    return x, z, points, quads


def fmt(v):
    return f"{v:.9g}"


def write(name, h):
    x, z, points, quads = mesh(h)
    length = x[-1]
    pts = ", ".join(f"[{fmt(px)}, {fmt(pz)}]" for px, pz in points)
    qs = ", ".join(f"[{a}, {b}, {c}, {d}]" for a, b, c, d in quads)
    text = f'''# Notched ply strip pulled along its fibres ({name} mesh: h = {h * 1e3:g} mm
# across the crack path). Written by examples/sections/notched_strip.py;
# the crack-band check of docs/composites.md ("Ply damage").
#
# Section x ∈ [0, {fmt(length * 1e3)}] mm along the fibres (axis 1 = x: the
# material's own axes), z ∈ [0, 6.4] mm; a notch one element wide from z = 0
# to 1.6 mm at x = 2 + h/2 mm, so the ligament is 4.8 mm; one B2 element of
# depth 1 mm along y (u_y free at y = 1 mm). The end x = 0 is held in x, the
# end x = L pulled by 0.15 mm in x; the crack crosses the ligament in fibre
# tension. IM7/8552-like ply (Camanho, Maimí & Dávila 2007, Compos. Sci.
# Technol. 67:2715; values as in design 48 §3.5): l_ch = E1 G_FT/Xt² =
# 4.2 mm, so every band here is far below 2 l_ch (no strength reduction).
#
# Expected (crack band, Bažant & Oh 1983): the energy dissipated in fibre
# tension is G_FT × ligament × depth = 133e3 × 4.8e-3 × 1e-3 = 0.638 J,
# whatever h (crates/cufem-cli/tests/ply_damage.rs).

title = "Notched IM7/8552 strip in fibre tension, h = {h * 1e3:g} mm"

[solver]
increments = 150
# the damage's viscosity (1e-3 in load-factor units) makes the path depend
# on the step: the dissipated energy changes by 0.4 % from 2e-3 to 1e-3 and
# by 0.01 % from 1e-3 to 5e-4 (coarse mesh), so the step is held at 1e-3
max_increment = 0.001
max_increments = 5000
# a crack that closes again near the notch root switches a point between
# its open and closed stiffness: without line search the fine mesh's Newton
# cycles there at λ = 0.91
line_search = true

[[materials]]
name = "im7_8552"
orthotropic = {{ e1 = 171.42e9, e2 = 9.08e9, e3 = 9.08e9, g12 = 5.29e9, g13 = 5.29e9, g23 = 2.98e9, nu12 = 0.32, nu13 = 0.32, nu23 = 0.52 }}
# the matrix strengths and energies raised out of reach (this example
# checks the fibre-tension band alone; with IM7's own matrix values the
# notch root cracks in matrix tension first)
strengths = {{ xt = 2326.2e6, xc = 1200.1e6, yt = 5e9, yc = 5e9, s12 = 3e9, s23 = 3e9 }}
damage = {{ fibre_tension = 133.3e3, fibre_compression = 61.0e3, matrix_tension = 1e7, matrix_compression = 1e7, viscosity = 1e-3 }}

[[bodies]]
name = "strip"
material = "im7_8552"
axis = {{ element = "B2", from = 0.0, to = {fmt(T)}, elements = 1 }}
section = {{ shape = "quads", element = "L4", points = [{pts}], quads = [{qs}] }}

[[constraints]]
name = "held"
body = "strip"
where = {{ x = 0.0 }}
fix = ["x"]

[[constraints]]
name = "pull"
body = "strip"
where = {{ x = {fmt(length)} }}
displacement = {{ x = 1.5e-4 }}

[[constraints]]
name = "depth"
body = "strip"
where = {{ y = 0.0 }}
fix = ["y"]

[[constraints]]
name = "corner"
body = "strip"
where = {{ x = 0.0, z = 0.0 }}
fix = ["z"]
'''
    with open(f"examples/notched_strip_{name}.toml", "w") as f:
        f.write(text)


if __name__ == "__main__":
    for name, h in MESHES.items():
        write(name, h)
