"""``Domain.cell_fractions`` against references computed without the library: revolved
(r-z) fractions and centroids of a disc against 30-digit mpmath quadrature per cell; closed
volumes (sphere, ellipse, torus from one closed NURBS curve, several contours, a disc with a
hole) by Pappus; Axom's shaping cases (llnl/axom issues #996, #998, #999: contours revolved
about an axis, a circle as one closed contour, contours not monotone in x or y); the embedded
boundary's length, centroid and normal and the faces' apertures and centroids against shapely
clipping of a finely flattened boundary (circle, tilted ellipse, a star-shaped closed cubic
B-spline), whose chord error each test measures and keeps well below its tolerance.

mpmath and shapely are imported outright: CI installs both (``.ci/run``), so a missing one
fails these tests instead of skipping them.
"""

import functools
import math

import mpmath
import numpy as np
import pytest
import shapely

import inrs

S = math.sqrt(0.5)


# ---------------------------------------------------------------------------------------------
# Domains, built as NURBS here (and their exact parametrizations for the references).


def nurbs_circle(cx: float, cy: float, r: float) -> dict:
    """A full circle as ONE closed rational quadratic NURBS curve (nine control points)."""
    unit = [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]]
    return {
        "degree": 2,
        "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
        "control_points": [[cx + r * u, cy + r * v] for u, v in unit],
        "weights": [1, S, 1, S, 1, S, 1, S, 1],
    }


def circle_domain(cx: float, cy: float, r: float) -> inrs.Domain:
    return inrs.Domain.from_curves([nurbs_circle(cx, cy, r)])


def half_disc(r: float, axis: str) -> inrs.Domain:
    """The half of the disc of radius ``r`` about the origin on the positive side of the axis
    of revolution (``'y'``: x >= 0, ``'x'``: y >= 0): a semicircle of two rational quadratic
    quarters, closed by a segment on the axis."""
    pts = [[0, -r], [r, -r], [r, 0], [r, r], [0, r]]
    chord = [[0, r], [0, -r]]
    if axis == "x":  # rotate by -90 degrees: (x, y) -> (-y, x) maps x >= 0 to y >= 0
        pts = [[-y, x] for x, y in pts]
        chord = [[-y, x] for x, y in chord]
    arc = {"degree": 2, "knots": [0, 0, 0, 0.5, 0.5, 1, 1, 1], "control_points": pts}
    arc["weights"] = [1, S, 1, S, 1]
    segment = {"degree": 1, "knots": [0, 0, 1, 1], "control_points": chord}
    return inrs.Domain.from_curves([arc, segment])


def ellipse_domain(cx, cy, rx, ry, tilt) -> inrs.Domain:
    d = inrs.Domain.from_json(
        '{"curves": [{"ellipse": '
        f'{{"center": [{cx!r}, {cy!r}], "rx": {rx!r}, "ry": {ry!r}, "tilt": {tilt!r}}}}}]}}'
    )
    # Pin the reference's reading of "tilt" (radians, counter-clockwise): the major axis'
    # tip turned by +tilt is inside, turned by -tilt is outside.
    tips = [[cx + 0.98 * rx * math.cos(t), cy + 0.98 * rx * math.sin(t)] for t in (tilt, -tilt)]
    assert d.contains_xy(np.array(tips)).tolist() == [True, False]
    return d


# The star: a closed (periodic, unclamped) uniform cubic B-spline whose 30 control points wind
# five times in and out: not monotone in x or in y (8 turning points in each).
STAR_CENTER = (2.5, 0.3)


def star_controls() -> np.ndarray:
    n = 30
    th = 2 * np.pi * np.arange(n) / n
    rho = 1.0 + 0.55 * np.cos(5 * th) + 0.12 * np.sin(3 * th + 0.4)
    return np.c_[STAR_CENTER[0] + rho * np.cos(th), STAR_CENTER[1] + 0.8 * rho * np.sin(th)]


def star_domain() -> inrs.Domain:
    p = star_controls()
    # Periodic form: the first three control points repeated, uniform knots 0 .. n + 6, the
    # curve on [3, n + 3] (its ends meet: C2 all round).
    q = np.r_[p, p[:3]]
    knots = np.arange(len(q) + 4, dtype=float)
    return inrs.Domain.from_curves([{"degree": 3, "knots": knots, "control_points": q}])


def star_points(m: int) -> np.ndarray:
    """``m`` points per knot span of the star at uniform parameters (``30 m`` in all, the
    closing point not repeated), from the uniform cubic B-spline's span polynomials (its
    blending functions written out, independently of the library's evaluator)."""
    p = star_controls()
    n = len(p)
    u = np.arange(m) / m
    b = np.stack([(1 - u) ** 3, 3 * u**3 - 6 * u**2 + 4, -3 * u**3 + 3 * u**2 + 3 * u + 1, u**3]) / 6
    return np.vstack([b.T @ p[[k, (k + 1) % n, (k + 2) % n, (k + 3) % n]] for k in range(n)])


def chord_error(points: np.ndarray, mids: np.ndarray) -> float:
    """The largest distance from a point of the curve at each chord's middle parameter to
    the chord (``points[k]`` to ``points[k + 1]``, closing)."""
    a, b = points, np.roll(points, -1, axis=0)
    d = b - a
    cross = d[:, 0] * (mids[:, 1] - a[:, 1]) - d[:, 1] * (mids[:, 0] - a[:, 0])
    return float(np.max(np.abs(cross) / np.hypot(d[:, 0], d[:, 1])))


# Fine flattenings, about two million points per loop; each returns (points, chord error).
N_FINE = 2_000_000


def ellipse_points(cx, cy, rx, ry, tilt, n):
    t = 2 * np.pi * np.arange(n) / n
    c, s = math.cos(tilt), math.sin(tilt)
    ex, ey = rx * np.cos(t), ry * np.sin(t)
    return np.c_[cx + c * ex - s * ey, cy + s * ex + c * ey]


@functools.lru_cache(maxsize=None)
def fine_ellipse(cx, cy, rx, ry, tilt):
    pts = ellipse_points(cx, cy, rx, ry, tilt, N_FINE)
    mids = ellipse_points(cx, cy, rx, ry, tilt, 2 * N_FINE)[1::2]
    return pts, chord_error(pts, mids)


@functools.lru_cache(maxsize=None)
def fine_star():
    # Twice the points of the conics: its tightest bends would otherwise leave a chord error
    # of 1.7e-11, too close to 1e-10 of a cell.
    m = 2 * N_FINE // 30 + 1
    pts = star_points(m)
    return pts, chord_error(pts, star_points(2 * m)[1::2])


def ccw(points: np.ndarray) -> np.ndarray:
    """The points ordered counter-clockwise (the domain on the left), checked by the signed
    (shoelace) area."""
    x, y = points[:, 0], points[:, 1]
    signed = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    assert signed != 0
    return points if signed > 0 else points[::-1].copy()


def ring_moments(xs, ys):
    """``(ny, nx)``: ``int int_cell x dA`` = ``h (x1^2 - x0^2) / 2``, a ring's volume over 2 pi."""
    return np.outer(np.diff(ys), np.diff(np.asarray(xs) ** 2) / 2)


def ring_volumes(xs, ys, axis):
    """``(ny, nx)``: the volume the cell sweeps about the axis, ``pi h (r1^2 - r0^2)``."""
    if axis == "y":
        return np.outer(np.diff(ys), math.pi * np.diff(np.asarray(xs) ** 2))
    return np.outer(math.pi * np.diff(np.asarray(ys) ** 2), np.diff(xs))


def revolved_volume(d: inrs.Domain, xs, ys, axis) -> float:
    f = d.cell_fractions(xs, ys, axisymmetric=axis)
    return math.fsum((f * ring_volumes(xs, ys, axis)).ravel())


# ---------------------------------------------------------------------------------------------
# 1. Revolved cells against mpmath.


def disc_moments_mp(a, b, r, xs, ys):
    """Per cell ``[x_i, x_i+1] x [y_j, y_j+1]``: ``(int int x dA, int int x^2 dA, int int x y
    dA)`` over the cell's part of the disc of centre ``(a, b)`` and radius ``r``, at 30
    digits: the integral over x of the moments of the chord ``[y0, y1] ∩ [b - s, b + s]``,
    ``s = sqrt(r^2 - (x - a)^2)``, split where a chord end crosses ``y0`` or ``y1`` and at
    ``a -+ r`` (mpmath.quad's tanh-sinh rule takes the square root's end points)."""
    out = np.zeros((len(ys) - 1, len(xs) - 1, 3))
    with mpmath.workdps(30):
        a, b, r = mpmath.mpf(a), mpmath.mpf(b), mpmath.mpf(r)

        def s(x):
            return mpmath.sqrt(max(r * r - (x - a) ** 2, 0))

        for j in range(len(ys) - 1):
            y0, y1 = mpmath.mpf(ys[j]), mpmath.mpf(ys[j + 1])
            cuts = [a - r, a + r]
            for y in (y0, y1):
                if abs(y - b) < r:
                    h = mpmath.sqrt(r * r - (y - b) ** 2)
                    cuts += [a - h, a + h]
            for i in range(len(xs) - 1):
                lo, hi = max(mpmath.mpf(xs[i]), a - r), min(mpmath.mpf(xs[i + 1]), a + r)
                if lo >= hi:
                    continue
                pts = sorted({lo, hi, *[c for c in cuts if lo < c < hi]})
                m0 = mx = my = mpmath.mpf(0)
                for u, v in zip(pts[:-1], pts[1:]):
                    mid = (u + v) / 2
                    top_const, bot_const = b + s(mid) >= y1, b - s(mid) <= y0
                    top = (lambda x: y1) if top_const else (lambda x: b + s(x))
                    bot = (lambda x: y0) if bot_const else (lambda x: b - s(x))
                    if top(mid) <= bot(mid):
                        continue
                    if top_const and bot_const:  # the whole chord: polynomials
                        m0 += (y1 - y0) * (v**2 - u**2) / 2
                        mx += (y1 - y0) * (v**3 - u**3) / 3
                        my += (y1**2 - y0**2) / 2 * (v**2 - u**2) / 2
                        continue
                    m0 += mpmath.quad(lambda x: x * (top(x) - bot(x)), [u, v])
                    mx += mpmath.quad(lambda x: x * x * (top(x) - bot(x)), [u, v])
                    my += mpmath.quad(lambda x: x * (top(x) ** 2 - bot(x) ** 2) / 2, [u, v])
                out[j, i] = [float(m0), float(mx), float(my)]
    return out


@pytest.mark.parametrize("axis", ["y", "x"])
def test_revolved_disc_cells_equal_mpmath_quadrature(axis):
    # A disc of radius 1 whose centre is 2 from the axis (a torus), on a grid off the axis.
    radial, along = np.linspace(0.6, 3.4, 25), np.linspace(-1.3, 1.3, 22)
    if axis == "y":
        d, xs, ys = circle_domain(2.0, 0.0, 1.0), radial, along
    else:
        d, xs, ys = circle_domain(0.0, 2.0, 1.0), along, radial
    cov = d.cell_fractions(xs, ys, centroids=True, axisymmetric=axis)
    # The reference in (radius, along) coordinates; about x the roles swap (transpose).
    m = disc_moments_mp(2.0, 0.0, 1.0, radial, along)
    ring = ring_moments(radial, along)
    want_f = m[..., 0] / ring
    with np.errstate(invalid="ignore", divide="ignore"):
        want_r, want_z = m[..., 1] / m[..., 0], m[..., 2] / m[..., 0]
    size_r, size_z = np.diff(radial)[None, :], np.diff(along)[:, None]
    if axis == "x":
        want_f, want_r, want_z = want_f.T, want_r.T, want_z.T
        size_r, size_z = size_r.T, size_z.T
        got_r, got_z = cov.centroids[..., 1], cov.centroids[..., 0]
    else:
        got_r, got_z = cov.centroids[..., 0], cov.centroids[..., 1]
    # The reference itself, summed over the cells: the disc's moments in closed form, area
    # times R (the torus' 2 pi^2 r^2 R over 2 pi), A (R^2 + r^2 / 4), and 0 (centred on z = 0).
    assert math.fsum(m[..., 0].ravel()) == pytest.approx(2 * math.pi, rel=1e-14)
    assert math.fsum(m[..., 1].ravel()) == pytest.approx(math.pi * 4.25, rel=1e-14)
    assert abs(math.fsum(m[..., 2].ravel())) <= 1e-14
    err_f = np.abs(cov.fractions - want_f)
    assert err_f.max() <= 1e-12, (err_f.max(), np.unravel_index(err_f.argmax(), err_f.shape))
    cut = (want_f > 0) & (want_f < 1)
    assert cut.sum() > 60
    # r-weighted centroids, relative to the cell's size along each coordinate.
    big = want_f > 1e-6
    err_r = np.abs(got_r - want_r)[big] / np.broadcast_to(size_r, want_f.shape)[big]
    err_z = np.abs(got_z - want_z)[big] / np.broadcast_to(size_z, want_f.shape)[big]
    assert max(err_r.max(), err_z.max()) <= 1e-10, (err_r.max(), err_z.max())
    assert np.array_equal(np.isnan(cov.centroids[..., 0]), cov.fractions == 0)
    print(f"axis {axis}: fractions {err_f.max():.2e}, centroids {max(err_r.max(), err_z.max()):.2e} of the cell")


# ---------------------------------------------------------------------------------------------
# 2. Spheres and Pappus.


@pytest.mark.parametrize("axis", ["y", "x"])
def test_a_revolved_half_disc_is_a_ball(axis):
    r = 0.8
    radial = np.geomspace(1, 3, 41) - 1  # 0 .. 2, finer near the axis
    along = np.linspace(-0.93, 0.87, 37)
    xs, ys = (radial, along) if axis == "y" else (along, radial)
    v = revolved_volume(half_disc(r, axis), xs, ys, axis)
    assert v == pytest.approx(4 / 3 * math.pi * r**3, rel=1e-12, abs=0)


@pytest.mark.parametrize("axis", ["y", "x"])
def test_a_revolved_tilted_ellipse_follows_pappus(axis):
    rx, ry, tilt, dist, off = 0.9, 0.35, 0.6, 1.7, -0.2
    if axis == "y":
        d = ellipse_domain(dist, off, rx, ry, tilt)
        xs, ys = np.linspace(0.3, 3.1, 31), np.linspace(-1.1, 0.9, 27)
    else:
        d = ellipse_domain(off, dist, rx, ry, tilt)
        xs, ys = np.linspace(-1.1, 0.9, 27), np.linspace(0.3, 3.1, 31)
    # Pappus: the area pi a b times the path 2 pi d of its centroid (the centre).
    want = 2 * math.pi * dist * math.pi * rx * ry
    assert revolved_volume(d, xs, ys, axis) == pytest.approx(want, rel=1e-12)


# ---------------------------------------------------------------------------------------------
# 3. Axom's shaping cases (llnl/axom #996, #998, #999).


@pytest.mark.parametrize("axis", ["y", "x"])
def test_axom_a_circle_as_one_closed_contour_revolves_into_a_torus(axis):
    # Axom needed the circle split into two semicircles; here it is one NURBS curve.
    r, big_r, z = 0.45, 1.3, 0.2
    d = circle_domain(big_r, z, r) if axis == "y" else circle_domain(z, big_r, r)
    assert len(d.loops) == 1 and d.summary().curves == 1
    radial, along = np.linspace(0.0, 2.0, 33), np.linspace(-0.4, 0.8, 19)
    xs, ys = (radial, along) if axis == "y" else (along, radial)
    assert revolved_volume(d, xs, ys, axis) == pytest.approx(2 * math.pi**2 * r**2 * big_r, rel=1e-12)


@pytest.mark.parametrize("axis", ["y", "x"])
def test_axom_several_contours_revolve_by_pappus(axis):
    def place(cx, cy):
        return (cx, cy) if axis == "y" else (cy, cx)

    radial, along = np.linspace(0.0, 4.0, 41), np.linspace(-1.2, 1.1, 29)
    xs, ys = (radial, along) if axis == "y" else (along, radial)
    # Two disjoint discs.
    two = inrs.Domain.from_curves([nurbs_circle(*place(1.0, 0.4), 0.5), nurbs_circle(*place(2.9, -0.3), 0.7)])
    assert len(two.loops) == 2
    want = 2 * math.pi * (math.pi * 0.5**2 * 1.0 + math.pi * 0.7**2 * 2.9)
    assert revolved_volume(two, xs, ys, axis) == pytest.approx(want, rel=1e-12)
    # A disc with an off-centre hole (even-odd).
    holed = inrs.Domain.from_curves([nurbs_circle(*place(2.2, 0.0), 1.0), nurbs_circle(*place(2.45, 0.1), 0.4)])
    assert len(holed.loops) == 2
    want = 2 * math.pi * (math.pi * 1.0 * 2.2 - math.pi * 0.4**2 * 2.45)
    assert revolved_volume(holed, xs, ys, axis) == pytest.approx(want, rel=1e-12)


def polygon_cells(poly, xs, ys):
    """Per cell the area and the first moment ``int int x dA`` of ``poly ∩ cell``, by
    shapely: row strips clipped from the polygon, then each cell's overlay."""
    ny, nx = len(ys) - 1, len(xs) - 1
    area, mx = np.zeros((ny, nx)), np.zeros((ny, nx))
    for j in range(ny):
        strip = shapely.clip_by_rect(poly, xs[0] - 1, ys[j], xs[-1] + 1, ys[j + 1])
        if strip.is_empty:
            continue
        for i in range(nx):
            piece = shapely.intersection(strip, shapely.box(xs[i], ys[j], xs[i + 1], ys[j + 1]))
            if not piece.is_empty and piece.area > 0:
                area[j, i] = piece.area
                mx[j, i] = piece.area * piece.centroid.x
    return area, mx


def test_axom_a_non_monotone_spline_revolves_as_its_fine_polygon():
    d = star_domain()
    pts, chord = fine_star()
    poly = shapely.Polygon(pts)
    assert poly.is_valid and len(pts) >= 200_000
    xs, ys = np.linspace(0.9, 4.15, 26), np.linspace(-1.0, 1.62, 22)
    h = min(np.diff(xs).min(), np.diff(ys).min())
    # The polygon's area misses at most (2/3) chord x length per cell: keep it far below the
    # per-cell tolerance 1e-9 of the ring (about h^2 r).
    assert chord < 1e-10 * h, chord
    x0, y0, x1, y1 = poly.bounds
    assert xs[0] < x0 and x1 < xs[-1] and ys[0] < y0 and y1 < ys[-1]
    assert d.area == pytest.approx(poly.area, rel=1e-9)
    # The whole revolved volume: Pappus from the polygon's area and centroid.
    want = 2 * math.pi * poly.area * poly.centroid.x
    got = revolved_volume(d, xs, ys, "y")
    assert got == pytest.approx(want, rel=1e-9)
    # Per cell: int int x dA of the polygon's part against the fraction of the ring's.
    f = d.cell_fractions(xs, ys, axisymmetric="y")
    area, mx = polygon_cells(poly, xs, ys)
    ring = ring_moments(xs, ys)
    assert math.fsum(area.ravel()) == pytest.approx(poly.area, rel=1e-12)
    err = np.abs(f * ring - mx) / ring
    assert err.max() <= 1e-9, (err.max(), np.unravel_index(err.argmax(), err.shape))
    assert ((f > 0) & (f < 1)).sum() > 80
    print(f"star revolved: total {abs(got / want - 1):.2e}, worst cell {err.max():.2e} (chord {chord:.1e})")


# ---------------------------------------------------------------------------------------------
# 4. and 5. The embedded boundary and the faces against shapely.


def boundary_cells(ring, xs, ys):
    """Per cell, from the closed counter-clockwise polyline ``ring`` clipped by shapely: the
    length inside the cell, its length-weighted midpoint sum, and ``sum (dy, -dx)``."""
    ny, nx = len(ys) - 1, len(xs) - 1
    length, moment, normal = np.zeros((ny, nx)), np.zeros((ny, nx, 2)), np.zeros((ny, nx, 2))
    line = shapely.LineString(np.r_[ring, ring[:1]])
    for j in range(ny):
        strip = shapely.clip_by_rect(line, xs[0] - 1, ys[j], xs[-1] + 1, ys[j + 1])
        if strip.is_empty:
            continue
        for i in range(nx):
            piece = shapely.intersection(strip, shapely.box(xs[i], ys[j], xs[i + 1], ys[j + 1]))
            for part in shapely.get_parts(piece):
                if part.geom_type != "LineString":
                    continue  # a point where the curve grazes the cell
                c = shapely.get_coordinates(part)
                dd = np.diff(c, axis=0)
                seg = np.hypot(dd[:, 0], dd[:, 1])
                length[j, i] += seg.sum()
                moment[j, i] += (seg[:, None] * (c[1:] + c[:-1]) / 2).sum(axis=0)
                normal[j, i] += [dd[:, 1].sum(), -dd[:, 0].sum()]
    return length, moment, normal


def face_cells(poly, xs, ys):
    """The covered length and the centroid (the coordinate along the face) of every vertical
    face ``(ny, nx + 1)`` and horizontal face ``(ny + 1, nx)``: the face's line intersected
    with the polygon by shapely (midpoint-weighted over the covered pieces)."""
    out = []
    for edges, other, vertical in ((xs, ys, True), (ys, xs, False)):
        n_face, n_other = len(edges), len(other) - 1
        cover, centre = np.zeros((n_other, n_face)), np.full((n_other, n_face), np.nan)
        half = 0.25 * np.diff(edges).min()

        def seg(c, a, b):
            return shapely.LineString([(c, a), (c, b)] if vertical else [(a, c), (b, c)])

        for k, c in enumerate(edges):
            # The polygon near the line first (a narrow band about it), then the line.
            lo, hi = other[0] - 1, other[-1] + 1
            rect = (c - half, lo, c + half, hi) if vertical else (lo, c - half, hi, c + half)
            near = shapely.clip_by_rect(poly, *rect)
            full = shapely.intersection(seg(c, other[0], other[-1]), near)
            for j in range(n_other):
                piece = shapely.intersection(full, seg(c, other[j], other[j + 1]))
                total = weighted = 0.0
                for part in shapely.get_parts(piece):
                    if part.geom_type != "LineString":
                        continue
                    q = shapely.get_coordinates(part)[:, 1 if vertical else 0]
                    ln = np.abs(np.diff(q))
                    total += ln.sum()
                    weighted += (ln * (q[1:] + q[:-1]) / 2).sum()
                cover[j, k] = total
                if total > 0:
                    centre[j, k] = weighted / total
        out += [cover, centre] if vertical else [cover.T, centre.T]
    return out


CIRCLE = (0.13, -0.07, 1.0)
ELLIPSE = (0.1, 0.05, 1.4, 0.6, 0.5)


def irregular(lo, hi, n, seed):
    g = np.random.default_rng(seed)
    e = np.cumsum(g.uniform(0.6, 1.4, n))
    return lo + (hi - lo) * np.r_[0.0, e] / e[-1]


def shape_case(name):
    """(domain, fine counter-clockwise points, their chord error, x edges, y edges)."""
    if name == "circle":
        cx, cy, r = CIRCLE
        pts = ellipse_points(cx, cy, r, r, 0.0, N_FINE)
        chord = r * (1 - math.cos(math.pi / N_FINE))
        # x = -0.867 and 1.128 pass 0.003 and 0.002 from the vertical tangents x = -0.87, 1.13:
        # there the polyline's crossings are off by chord / sin(angle), the reference's worst
        # (lengths 6.2e-10, 1.8e-10, 3.4e-11 of a cell at 1, 2, 4 million points).
        return circle_domain(*CIRCLE), pts, chord, np.linspace(-1.2, 1.35, 24), np.linspace(-1.3, 1.15, 22)
    if name == "ellipse":
        pts, chord = fine_ellipse(*ELLIPSE)
        return ellipse_domain(*ELLIPSE), pts, chord, irregular(-1.45, 1.6, 26, 1), irregular(-0.95, 1.0, 17, 2)
    pts, chord = fine_star()
    return star_domain(), pts, chord, np.linspace(0.9, 4.15, 26), np.linspace(-1.0, 1.62, 22)


@functools.lru_cache(maxsize=None)
def shape_reference(name):
    d, pts, chord, xs, ys = shape_case(name)
    pts = ccw(pts)
    assert len(pts) >= 200_000
    eb = d.cell_fractions(xs, ys, True, True, boundary=True, face_centroids=True)
    return d, pts, chord, xs, ys, eb


@pytest.mark.parametrize("name", ["circle", "ellipse", "star"])
def test_embedded_boundary_equals_shapely_clipping_of_the_fine_curve(name):
    d, pts, chord, xs, ys, eb = shape_reference(name)
    dx, dy = np.diff(xs)[None, :], np.diff(ys)[:, None]
    size = np.minimum(dx, dy)
    # The polyline's chord error moves its clipped centroids by about (2/3) chord and its
    # crossings of the cell sides by chord / sin(angle): keep it 10 times below 1e-9 h.
    assert chord < 1e-10 * size.min(), chord
    length, moment, normal = boundary_cells(pts, xs, ys)
    assert math.fsum(length.ravel()) == pytest.approx(math.fsum(eb.boundary_lengths.ravel()), rel=1e-11)
    err_len = np.abs(eb.boundary_lengths - length) / size
    assert err_len.max() <= 1e-9, (err_len.max(), np.unravel_index(err_len.argmax(), err_len.shape))
    # Centroids and normals where the curve really crosses the cell (not grazing a corner).
    real = length >= 1e-7 * size
    assert real.sum() > 40
    with np.errstate(invalid="ignore", divide="ignore"):
        centroid = moment / length[..., None]
        unit = normal / np.hypot(normal[..., 0], normal[..., 1])[..., None]
    sizes = np.stack([np.broadcast_to(dx, size.shape), np.broadcast_to(dy, size.shape)], -1)
    err_c = (np.abs(eb.boundary_centroids - centroid) / sizes)[real].max()
    err_n = np.abs(eb.boundary_normals - unit)[real].max()
    assert err_c <= 1e-9 and err_n <= 1e-9, (err_c, err_n)
    # No boundary where shapely finds none.
    assert np.all(eb.boundary_lengths[length == 0] == 0)
    print(f"{name}: length {err_len.max():.2e}, centroid {err_c:.2e} of the cell, normal {err_n:.2e} (chord {chord:.1e})")


@pytest.mark.parametrize("name", ["circle", "ellipse", "star"])
def test_consistency_the_normals_obey_the_divergence_theorem_per_cell(name):
    # A consistency check of the library's own outputs (not an independent reference): the
    # normal integral over the boundary in a cell is minus the covered faces' flux.
    d, pts, chord, xs, ys, eb = shape_reference(name)
    dx, dy = np.diff(xs)[None, :], np.diff(ys)[:, None]
    flux_x = (eb.x_apertures[:, 1:] - eb.x_apertures[:, :-1]) * dy
    flux_y = (eb.y_apertures[1:] - eb.y_apertures[:-1]) * dx
    flux = np.stack([flux_x, flux_y], -1)
    size = np.hypot(flux_x, flux_y)
    has = size > 0
    cell = np.broadcast_to(np.minimum(dx, dy), size.shape)
    err = np.abs(eb.boundary_normals * size[..., None] + flux)[has] / cell[has][:, None]
    assert err.max() <= 1e-12, err.max()
    assert np.isnan(eb.boundary_normals[~has]).all()


@pytest.mark.parametrize("name", ["circle", "ellipse", "star"])
def test_apertures_and_face_centroids_equal_shapely_on_the_fine_polygon(name):
    d, pts, chord, xs, ys, eb = shape_reference(name)
    poly = shapely.Polygon(pts)
    assert poly.is_valid
    x_cover, x_centre, y_cover, y_centre = face_cells(poly, xs, ys)
    errs = []
    for cover, centre, aperture, got, face in (
        (x_cover, x_centre, eb.x_apertures, eb.x_face_centroids, np.diff(ys)[:, None]),
        (y_cover, y_centre, eb.y_apertures, eb.y_face_centroids, np.diff(xs)[None, :]),
    ):
        face = np.broadcast_to(face, cover.shape)
        err_a = np.abs(aperture - cover / face)
        assert err_a.max() <= 1e-9, (err_a.max(), np.unravel_index(err_a.argmax(), err_a.shape))
        assert np.all(np.isnan(got[cover == 0]))
        real = cover >= 1e-7 * face
        assert real.sum() > 20
        err_c = np.abs(got - centre)[real] / face[real]
        assert err_c.max() <= 1e-9, err_c.max()
        errs += [err_a.max(), err_c.max()]
    print(f"{name}: apertures {max(errs[0], errs[2]):.2e}, face centroids {max(errs[1], errs[3]):.2e} of the face")
