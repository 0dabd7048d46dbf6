#!/usr/bin/env python3
"""Writes examples/notched_strip_{coarse,medium,fine}.toml: a notched ply strip
pulled along its fibres, at three element sizes h around the crack path
(the crack-band check of docs/composites.md, "Ply damage"), and
examples/notched_strip_snap_back.toml: a double-edge notched strip with long
arms pulled by an end force through its snap-back (path following).

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


def mesh(h, both_edges=False):
    """The grid's x lines, the crack column's index among the x intervals,
    the points and the quads: the column's bottom rows (and, with
    `both_edges`, its top rows) left out as the notch."""
    x, z, band = lines(h)
    rows, notch_rows = len(z) - 1, round(A / h)
    index, points, quads = {}, [], []

    def point(i, k):
        if (i, k) not in index:
            index[(i, k)] = len(points)
            points.append((x[i], z[k]))
        return index[(i, k)]

    for k in range(rows):
        for i in range(len(x) - 1):
            if i == band and (k < notch_rows or (both_edges and k >= rows - notch_rows)):
                continue
            # counter-clockwise in the x–z plane
            quads.append((point(i, k), point(i + 1, k), point(i + 1, k + 1), point(i, k + 1)))
    return x, band, points, quads


def fmt(v):
    return f"{v:.9g}"


def constraint(name, where, fix):
    """A [[constraints]] entry holding `fix` (a TOML list) at `where`."""
    return f'[[constraints]]\nname = "{name}"\nbody = "strip"\nwhere = {{ {where} }}\nfix = {fix}\n'


def write(name, h):
    x, _, points, quads = mesh(h)
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
# end x = L pulled by 0.15 mm in x; a fibre-tension crack starts at the notch
# root and crosses the strip, stepping towards the pulled end as it goes (the
# ends held flat, the eccentric ligament bends; crates/cufem-cli/tests/
# ply_damage.rs, docs/limitations.md). IM7/8552-like ply (Camanho, Maimí & Dávila 2007, Compos. Sci.
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

{constraint("held", "x = 0.0", '["x"]')}
[[constraints]]
name = "pull"
body = "strip"
where = {{ x = {fmt(length)} }}
displacement = {{ x = 1.5e-4 }}

{constraint("depth", "y = 0.0", '["y"]')}
{constraint("corner", "x = 0.0, z = 0.0", '["z"]')}'''
    with open(f"examples/notched_strip_{name}.toml", "w") as f:
        f.write(text)


# The snap-back strip: both edges notched (no bending under an end force),
# arms of SNAP_ARM beside the crack column, the coarse h.
SNAP_ARM = 20.0e-3
SNAP_H = 0.8e-3
SNAP_FORCE = 10.0e3  # reference load (N): λ = 1 is 10 kN


def write_snap_back(h=SNAP_H, name=None):
    """The snap-back strip at element size `h`; with `name`, the crack-band
    strip of that mesh (`fibre_shear = 0`, `softening_stress = "uniaxial"`,
    `max_damage = 0.9999`) as notched_strip_band_NAME.toml."""
    global S
    S, arm = SNAP_ARM, S
    x, band, points, quads = mesh(h, both_edges=True)
    S = arm
    length = x[-1]
    pts = ", ".join(f"[{fmt(px)}, {fmt(pz)}]" for px, pz in points)
    qs = ", ".join(f"[{a}, {b}, {c}, {d}]" for a, b, c, d in quads)
    text = f'''# A double-edge notched ply strip pulled by an end force through its
# snap-back. Written by examples/sections/notched_strip.py; docs/composites.md
# ("Ply damage", path following).
#
# Section x ∈ [0, {fmt(length * 1e3)}] mm along the fibres, z ∈ [0, 6.4] mm;
# notches one element (h = {h * 1e3:g} mm) wide from both edges, 1.6 mm
# deep, at x = {fmt(x[band] * 1e3)} mm: a ligament of 3.2 mm about the strip's
# axis, so the end force pulls it without bending. One B2 element of depth
# 1 mm along y. The end x = 0 is held in x; the end x = L carries a uniform
# traction of λ × {SNAP_FORCE / 1e3:g} kN, λ an unknown of the path
# following. Ply and its fibre-tension crack as in
# examples/notched_strip_coarse.toml, without viscosity.
#
# Why path following: the arms store ½ P u ≈ 0.78 J at the peak, more than
# the crack dissipates (G_FT × 3.2 mm × 1 mm = 0.43 J by the crack band;
# 1.31 times that here, docs/limitations.md), so
# past the peak the force and the end's displacement both fall (a
# snap-back): neither load nor displacement control follows it; the
# dissipation constraint does, each increment dissipating at most
# max_dissipation. Checked in crates/cufem-cli/tests/snap_back.rs: the peak
# against displacement control, the snap-back, the path's dissipation
# against the law's.

title = "Double-edge notched IM7/8552 strip through its snap-back, h = {h * 1e3:g} mm"

[solver]
control = "arc_length"
constraint = "dissipation"
# the pre-peak increments set the peak (damage at the notch roots): with a
# first Δλ of 1e-3 it is within 0.1 % of displacement control's
increments = 1000
max_dissipation = 0.001
max_increments = 3000
# the crack through: the crack column's right face, mid-ligament, 0.3 mm on
# (the arms have unloaded; the crack's own opening at full damage is 0.11 mm)
stop = {{ probe = "crack_right", component = "x", beyond = 3e-4 }}

[[materials]]
name = "im7_8552"
orthotropic = {{ e1 = 171.42e9, e2 = 9.08e9, e3 = 9.08e9, g12 = 5.29e9, g13 = 5.29e9, g23 = 2.98e9, nu12 = 0.32, nu13 = 0.32, nu23 = 0.52 }}
strengths = {{ xt = 2326.2e6, xc = 1200.1e6, yt = 5e9, yc = 5e9, s12 = 3e9, s23 = 3e9 }}
damage = {{ fibre_tension = 133.3e3, fibre_compression = 61.0e3, matrix_tension = 1e7, matrix_compression = 1e7 }}

[[bodies]]
name = "strip"
material = "im7_8552"
axis = {{ element = "B2", from = 0.0, to = {fmt(T)}, elements = 1 }}
section = {{ shape = "quads", element = "L4", points = [{pts}], quads = [{qs}] }}

[[loads]]
name = "pull"
body = "strip"
where = {{ x = {fmt(length)} }}
total_force = [{SNAP_FORCE!r}, 0.0, 0.0]

[[probes]]
name = "end"
point = [{fmt(length)}, 0.0, 0.0032]

[[probes]]
name = "crack_left"
point = [{fmt(x[band])}, 0.0, 0.0032]

[[probes]]
name = "crack_right"
point = [{fmt(x[band + 1])}, 0.0, 0.0032]

{constraint("held", "x = 0.0", '["x"]')}
{constraint("depth", "y = 0.0", '["y"]')}
{constraint("centre", "x = 0.0, z = 0.0032", '["z"]')}'''
    path = "examples/notched_strip_snap_back.toml"
    if name is not None:
        path, text = f"examples/notched_strip_band_{name}.toml", band_text(text, h, name)
    with open(path, "w") as f:
        f.write(text)


def band_text(text, h, name):
    """The snap-back strip's text made the crack-band check of mesh `name`."""
    header = f'''# The crack-band check, {name} mesh: the double-edge notched strip of
# examples/notched_strip_snap_back.toml (written by the same script,
# examples/sections/notched_strip.py) with h = {h * 1e3:g} mm across its
# crack path, followed through its snap-back by the dissipation of each
# increment; docs/composites.md ("Ply damage").
#
# Three material keys differ from the snap-back strip, each for a measured reason
# (docs/limitations.md "Ply damage"):
# * fibre_shear = 0 (Abaqus's α): with Hashin's 1 a notch root's shear at
#   onset sets a longer softening than the stretch that follows needs, and
#   the strip dissipates 1.31 G_FT A;
# * softening_stress = "uniaxial": the softening line drawn for E1 ε11, the
#   stress the cracked compliance leaves, not for the effective (C⁰ε)₁₁ —
#   the band, held laterally by the arms, then dissipates G/L: with
#   "effective" the strips give 0.984, 0.969, 0.954 of G_FT A, falling as
#   the band narrows;
# * max_damage = 0.9999: a cracked point keeps 1 − max_damage of its
#   stiffness, and the band strain at full opening is δf/h (δf = 2 G_FT/Xt
#   = 0.115 mm), so about (1 − max_damage) 2 E1 G_FT/(Xt² h) of the band's
#   energy stays stored, not dissipated: with the default 0.999 1 % at
#   h = 0.8 mm and 4 % at 0.2 mm, with 0.9999 a tenth of that.
#
# Expected (crack band, Bažant & Oh 1983): G_FT × ligament × depth =
# 133.3e3 × 3.2e-3 × 1e-3 = 0.427 J, whatever h (crates/cufem-cli/tests/
# snap_back.rs; measured 1.015, 1.010, 1.004 of it coarse to fine).

'''
    pieces = [
        ("through its snap-back, h", "for the crack band, h"),
        ("beyond = 3e-4 }", "beyond = 1.5e-4 }"),
        (
            "# the pre-peak increments set the peak (damage at the notch roots): with a\n"
            "# first Δλ of 1e-3 it is within 0.1 % of displacement control's\n",
            "# the pre-peak increments as the snap-back strip's (there they set the\n"
            "# peak within 0.1 % of displacement control's)\n",
        ),
        (
            "# the crack through: the crack column's right face, mid-ligament, 0.3 mm on\n"
            "# (the arms have unloaded; the crack's own opening at full damage is 0.11 mm)\n",
            "# the crack through: the crack column's right face, mid-ligament, 0.15 mm\n"
            "# on, past the full opening δf (0.12 mm) and before the increments on the\n"
            "# cracked column's 1e-4 of stiffness grow (one jumped to 29 mm past 0.3 mm)\n",
        ),
        ("matrix_compression = 1e7 }", 'matrix_compression = 1e7, fibre_shear = 0.0, softening_stress = "uniaxial", max_damage = 0.9999 }'),
    ]
    for old, new in pieces:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return header + text[text.index("title = "):]


if __name__ == "__main__":
    for name, h in MESHES.items():
        write(name, h)
    write_snap_back()
    for name, h in MESHES.items():
        write_snap_back(h, name)
