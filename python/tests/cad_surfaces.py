"""The surfaces of a STEP or IGES file evaluated in the file's own parameters, for the tests.

``inrs.cad_faces`` reads each face's loops in its surface's own ``(u, v)``: the one ISO
10303-42 defines for STEP surfaces, IGES 5.3 for IGES ones (and, for an IGES 108 plane, which
the standard does not parametrise, the axes the reader documents in
``crates/rs-io/src/cad/iges/faces.rs``). OpenCASCADE may parameterise the same surface
otherwise (an IGES surface of revolution has its ``u`` and ``v`` swapped, a swept curve is
re-framed, ...). To compare the two classifications on the same points,
:meth:`StepFile.face_surface` and :meth:`IgesFile.face_surface` give a face's surface as a
function ``(u, v) -> (x, y, z)`` written from the standards, from the numbers in the file
text; ``cad_files`` then finds those 3-D points on OCC's surface, hence OCC's ``(u, v)`` of
the same points.

Only what the real files of the tests need is read: STEP ``PLANE``, ``CYLINDRICAL_SURFACE``,
``CONICAL_SURFACE``, ``SPHERICAL_SURFACE``, ``TOROIDAL_SURFACE``, ``SURFACE_OF_REVOLUTION``
and ``SURFACE_OF_LINEAR_EXTRUSION`` with ``LINE``, ``CIRCLE`` or ``ELLIPSE`` curves, and
``B_SPLINE_SURFACE_WITH_KNOTS`` (simple, or the rational complex instance); IGES 108 plane, 120 surface
of revolution with 110 line or 100 circular arc generatrices and 128 rational B-spline
surface, each with its 124 transformation matrices. Anything else raises
:class:`Unsupported` (the caller reports the face). Lengths are in the file's unit, angles
(STEP) in its angle unit; the caller scales lengths to millimetres.

Not a reader: no bounds checks beyond what a test needs to fail with a message.
"""

from __future__ import annotations

import math
import re
from typing import Callable, Dict, List, Tuple

import numpy as np

#: ``(u, v) -> points``: an ``(n, 2)`` array of parameters to an ``(n, 3)`` array of points.
Surface = Callable[[np.ndarray], np.ndarray]


class Unsupported(ValueError):
    """A surface (or a curve in it) this module does not evaluate."""


def _unit(v: np.ndarray, what: str) -> np.ndarray:
    n = float(np.linalg.norm(v))
    if not (n > 0 and math.isfinite(n)):
        raise Unsupported(f"{what}: zero or non-finite direction {v}")
    return v / n


def rotate(points: np.ndarray, origin: np.ndarray, axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """``points`` (n, 3) turned by ``angle`` (n,) radians about the line through ``origin``
    along the unit ``axis``, counter-clockwise seen from the tip of ``axis`` (Rodrigues)."""
    r = points - origin
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    along = (r @ axis)[:, None] * axis
    return origin + r * c + np.cross(axis, r) * s + along * (1 - c)


def _basis(knots: np.ndarray, degree: int, t: float) -> Tuple[int, np.ndarray]:
    """``(span, [N_{span-degree}, ..., N_span](t))``: the B-spline basis functions that are
    nonzero at ``t`` (Cox-de Boor), ``t`` clamped to the knot vector's valid range."""
    lo, hi = knots[degree], knots[len(knots) - degree - 1]
    t = min(max(t, lo), hi)
    span = int(np.searchsorted(knots, t, side="right")) - 1
    span = min(max(span, degree), len(knots) - degree - 2)
    n = np.zeros(degree + 1)
    n[0] = 1.0
    left, right = np.zeros(degree + 1), np.zeros(degree + 1)
    for j in range(1, degree + 1):
        left[j], right[j] = t - knots[span + 1 - j], knots[span + j] - t
        saved = 0.0
        for r in range(j):
            tmp = n[r] / (right[r + 1] + left[j - r])
            n[r] = saved + right[r + 1] * tmp
            saved = left[j - r] * tmp
        n[j] = saved
    return span, n


def bspline_surface(
    degrees: Tuple[int, int], knots: Tuple[np.ndarray, np.ndarray], points: np.ndarray, weights: np.ndarray
) -> Surface:
    """The tensor-product rational B-spline ``S(u, v) = sum N_i(u) N_j(v) w_ij P_ij /
    sum N_i(u) N_j(v) w_ij``; ``points`` (nu, nv, 3) and ``weights`` (nu, nv) indexed
    ``[i along u, j along v]``."""
    (p, q), (ku, kv) = degrees, knots
    if points.shape[:2] != weights.shape or points.shape[0] != len(ku) - p - 1 or points.shape[1] != len(kv) - q - 1:
        raise Unsupported(f"B-spline sizes: {points.shape}, weights {weights.shape}, knots {len(ku)}, {len(kv)}")
    homogeneous = np.concatenate([points * weights[..., None], weights[..., None]], axis=2)

    def evaluate(uv: np.ndarray) -> np.ndarray:
        out = np.empty((len(uv), 3))
        for k, (u, v) in enumerate(uv):
            i, nu = _basis(ku, p, float(u))
            j, nv = _basis(kv, q, float(v))
            h = np.einsum("a,b,abk->k", nu, nv, homogeneous[i - p : i + 1, j - q : j + 1])
            out[k] = h[:3] / h[3]
        return out

    return evaluate


# --- STEP (ISO 10303-21 syntax, ISO 10303-42 geometry) ---------------------------------------

_STEP_TOKEN = re.compile(
    r"\s*(?:('(?:[^']|'')*')|(#\d+)|(\.[A-Za-z_0-9]+\.)|([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"
    r"|([A-Za-z_][A-Za-z_0-9]*)|([(),$*]))"
)


class StepFile:
    """The instances of a STEP file's DATA section, parsed on demand."""

    def __init__(self, text: str, rad_per_angle_unit: float = 1.0):
        start = text.find("DATA;")
        data = text[start:] if start >= 0 else text
        #: ``{123: "TYPE(...)"}``: each simple instance's text, strings kept whole.
        self.raw: Dict[int, str] = {
            int(m.group(1)): m.group(2)
            for m in re.finditer(r"#(\d+)\s*=\s*((?:'(?:[^']|'')*'|[^;'])*);", data)
        }
        self.rad = rad_per_angle_unit
        self._parsed: Dict[int, Tuple[str, list]] = {}

    def get(self, ref, *types: str) -> Tuple[str, list]:
        """``(TYPE, [arguments])`` of instance ``ref`` (``"#12"`` or 12), which must be one
        of ``types`` (any when none given)."""
        n = int(str(ref).lstrip("#"))
        if n not in self._parsed:
            if n not in self.raw:
                raise Unsupported(f"#{n}: no such instance")
            value = _parse_step(self.raw[n])
            if not (isinstance(value, tuple) and isinstance(value[1], list)):
                raise Unsupported(f"#{n}: not a simple instance: {self.raw[n][:60]}")
            self._parsed[n] = value
        kind, args = self._parsed[n]
        if types and kind not in types:
            raise Unsupported(f"#{n} is a {kind}, not {' or '.join(types)}")
        return kind, args

    def point(self, ref) -> np.ndarray:
        return np.array(self.get(ref, "CARTESIAN_POINT")[1][1], float)

    def direction(self, ref) -> np.ndarray:
        return _unit(np.array(self.get(ref, "DIRECTION")[1][1], float), f"#{ref}")

    def vector(self, ref) -> np.ndarray:
        _, args = self.get(ref, "VECTOR")
        return self.direction(args[1]) * _measure(args[2])

    def axis2(self, ref) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(location, x, y, z)`` of an AXIS2_PLACEMENT_3D (ISO 10303-42: ``z`` the axis,
        default (0, 0, 1); ``x`` the ref_direction made normal to ``z``, default (1, 0, 0),
        or (0, 1, 0) when ``z`` is along it (first_proj_axis); ``y = z x x``)."""
        _, args = self.get(ref, "AXIS2_PLACEMENT_3D")
        loc = self.point(args[1])
        z = self.direction(args[2]) if args[2] != "$" else np.array([0.0, 0.0, 1.0])
        if args[3] != "$":
            d = self.direction(args[3])
        else:
            d = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 1 - 1e-12 else np.array([0.0, 1.0, 0.0])
        x = _unit(d - (d @ z) * z, f"#{ref} ref_direction")
        return loc, x, np.cross(z, x), z

    def curve(self, ref) -> Callable[[np.ndarray], np.ndarray]:
        """The curve ``t (n,) -> points (n, 3)`` of a LINE, CIRCLE or ELLIPSE."""
        kind, args = self.get(ref)
        if kind == "LINE":  # pnt + t dir (dir a VECTOR: its magnitude is one unit of t)
            p, d = self.point(args[1]), self.vector(args[2])
            return lambda t: p + t[:, None] * d
        if kind in ("CIRCLE", "ELLIPSE"):  # c + r1 cos t x + r2 sin t y, t an angle
            c, x, y, _ = self.axis2(args[1])
            r1 = _measure(args[2])
            r2 = _measure(args[3]) if kind == "ELLIPSE" else r1
            rad = self.rad
            return lambda t: c + r1 * np.cos(rad * t)[:, None] * x + r2 * np.sin(rad * t)[:, None] * y
        raise Unsupported(f"#{int(str(ref).lstrip('#'))}: curve {kind}")

    def face_surface(self, face_ref) -> Tuple[str, Surface]:
        """``(type, surface)`` of an ADVANCED_FACE's face_geometry."""
        _, args = self.get(face_ref, "ADVANCED_FACE", "FACE_SURFACE")
        return self.surface(args[2])

    def surface(self, ref) -> Tuple[str, Surface]:
        """``(type, (u, v) -> points)`` with ISO 10303-42's parameterisation."""
        n = int(str(ref).lstrip("#"))
        if self.raw.get(n, "").lstrip().startswith("("):
            return self._complex_surface(n)
        kind, args = self.get(ref)
        rad = self.rad
        if kind == "PLANE":  # loc + u x + v y
            c, x, y, _ = self.axis2(args[1])
            return kind, lambda uv: c + uv[:, :1] * x + uv[:, 1:] * y
        if kind == "CYLINDRICAL_SURFACE":  # loc + r (cos u x + sin u y) + v z
            c, x, y, z = self.axis2(args[1])
            r = _measure(args[2])

            def cylinder(uv):
                u = rad * uv[:, :1]
                return c + r * (np.cos(u) * x + np.sin(u) * y) + uv[:, 1:] * z

            return kind, cylinder
        if kind == "CONICAL_SURFACE":  # loc + (r + v tan a)(cos u x + sin u y) + v z
            c, x, y, z = self.axis2(args[1])
            r, tan = _measure(args[2]), math.tan(rad * _measure(args[3]))

            def cone(uv):
                u, v = rad * uv[:, :1], uv[:, 1:]
                return c + (r + v * tan) * (np.cos(u) * x + np.sin(u) * y) + v * z

            return kind, cone
        if kind == "SPHERICAL_SURFACE":  # loc + r cos v (cos u x + sin u y) + r sin v z
            c, x, y, z = self.axis2(args[1])
            r = _measure(args[2])

            def sphere(uv):
                u, v = rad * uv[:, :1], rad * uv[:, 1:]
                return c + r * np.cos(v) * (np.cos(u) * x + np.sin(u) * y) + r * np.sin(v) * z

            return kind, sphere
        if kind == "TOROIDAL_SURFACE":  # loc + (R + r cos v)(cos u x + sin u y) + r sin v z
            c, x, y, z = self.axis2(args[1])
            big, small = _measure(args[2]), _measure(args[3])

            def torus(uv):
                u, v = rad * uv[:, :1], rad * uv[:, 1:]
                return c + (big + small * np.cos(v)) * (np.cos(u) * x + np.sin(u) * y) + small * np.sin(v) * z

            return kind, torus
        if kind == "SURFACE_OF_REVOLUTION":
            # The swept curve at v turned by the angle u about the axis (right-handed).
            curve = self.curve(args[1])
            _, a = self.get(args[2], "AXIS1_PLACEMENT")
            origin = self.point(a[1])
            axis = self.direction(a[2]) if a[2] != "$" else np.array([0.0, 0.0, 1.0])
            return kind, lambda uv: rotate(curve(uv[:, 1]), origin, axis, rad * uv[:, 0])
        if kind == "SURFACE_OF_LINEAR_EXTRUSION":  # the swept curve at u, moved by v V
            curve, d = self.curve(args[1]), self.vector(args[2])
            return kind, lambda uv: curve(uv[:, 0]) + uv[:, 1:] * d
        if kind == "B_SPLINE_SURFACE_WITH_KNOTS":
            # (name, u_degree, v_degree, control_points_list[i along u][j along v], form,
            # u_closed, v_closed, self_intersect, u_mults, v_mults, u_knots, v_knots, spec)
            p, q = int(args[1]), int(args[2])
            points = np.array([[self.point(r) for r in row] for row in args[3]], float)
            ku = np.repeat(np.array(args[10], float), np.array(args[8], int))
            kv = np.repeat(np.array(args[11], float), np.array(args[9], int))
            return kind, bspline_surface((p, q), (ku, kv), points, np.ones(points.shape[:2]))
        raise Unsupported(f"#{int(str(ref).lstrip('#'))}: surface {kind}")

    def _complex_surface(self, n: int) -> Tuple[str, Surface]:
        return _complex_b_spline_surface(self, n)


def _complex_b_spline_surface(file: "StepFile", n: int) -> Tuple[str, Surface]:
    """The rational B-spline surface of a complex instance ``#n = (B_SPLINE_SURFACE(...)
    B_SPLINE_SURFACE_WITH_KNOTS(...) RATIONAL_B_SPLINE_SURFACE(...) ...)``: its parts carry
    no name, so ``B_SPLINE_SURFACE``'s arguments are (u_degree, v_degree, points, form,
    u_closed, v_closed, self_intersect)."""
    value = _parse_step(file.raw[n])
    parts = {part[0]: part[1] for part in value if isinstance(part, tuple)} if isinstance(value, list) else {}
    if "B_SPLINE_SURFACE" not in parts or "B_SPLINE_SURFACE_WITH_KNOTS" not in parts:
        raise Unsupported(f"#{n}: complex instance without a B-spline surface")
    b, k = parts["B_SPLINE_SURFACE"], parts["B_SPLINE_SURFACE_WITH_KNOTS"]
    p, q = int(b[0]), int(b[1])
    points = np.array([[file.point(r) for r in row] for row in b[2]], float)
    ku = np.repeat(np.array(k[2], float), np.array(k[0], int))
    kv = np.repeat(np.array(k[3], float), np.array(k[1], int))
    rational = parts.get("RATIONAL_B_SPLINE_SURFACE")
    weights = np.array(rational[0], float) if rational else np.ones(points.shape[:2])
    return "RATIONAL_B_SPLINE_SURFACE", bspline_surface((p, q), (ku, kv), points, weights)


def _measure(value) -> float:
    """A number, or the number of a typed parameter such as ``LENGTH_MEASURE(1.)``."""
    if isinstance(value, tuple):
        value = value[1][0]
    if not isinstance(value, (int, float)):
        raise Unsupported(f"not a number: {value!r}")
    return float(value)


def _parse_step(text: str):
    """``TYPE(args)`` -> ``(TYPE, [args])``, lists for ``(...)``, floats, ``"#12"`` refs,
    ``".T."`` enums, ``"$"``/``"*"``, strings with their quotes."""
    tokens = []
    pos = 0
    while pos < len(text):
        m = _STEP_TOKEN.match(text, pos)
        if not m or m.end() == pos:
            if text[pos:].strip() == "":
                break
            raise Unsupported(f"cannot parse {text[pos:pos + 40]!r}")
        pos = m.end()
        string, ref, enum, number, word, punct = m.groups()
        if number is not None:
            tokens.append(("v", float(number)))
        elif word is not None:
            tokens.append(("w", word))
        elif punct is not None:
            tokens.append(("p", punct))
        else:
            tokens.append(("v", string or ref or enum))

    def value(i: int):
        kind, tok = tokens[i]
        if kind == "w":  # TYPE(args)
            if i + 1 < len(tokens) and tokens[i + 1] == ("p", "("):
                args, j = group(i + 1)
                return (tok, args), j
            return tok, i + 1
        if (kind, tok) == ("p", "("):
            return group(i)
        if kind == "p" and tok in "$*":
            return tok, i + 1
        if kind == "v":
            return tok, i + 1
        raise Unsupported(f"unexpected {tok!r}")

    def group(i: int):  # tokens[i] is "("
        out, i = [], i + 1
        while i < len(tokens) and tokens[i] != ("p", ")"):
            if tokens[i] == ("p", ","):
                i += 1
                continue
            v, i = value(i)
            out.append(v)
        return out, i + 1

    if not tokens:
        raise Unsupported("empty instance")
    return value(0)[0]


# --- IGES 5.3 (fixed 80-column ASCII form) ---------------------------------------------------

_HOLLERITH = re.compile(r"\s*(\d+)H")


class IgesFile:
    """The directory entries and parameter records of an IGES file."""

    def __init__(self, text: str):
        sections: Dict[str, List[str]] = {}
        for line in text.splitlines():
            if len(line) >= 73:
                sections.setdefault(line[72], []).append(line)
        glob = "".join(line[:72] for line in sections.get("G", []))
        self.delim, self.end = ",", ";"
        if glob.startswith("1H"):
            self.delim = glob[2]
            rest = glob[4:]
        else:
            rest = glob[1:]
        if rest.startswith("1H"):
            self.end = rest[2]
        d = sections.get("D", [])
        #: ``{de: (type, param start, param lines, transform pointer, form)}``.
        self.dir: Dict[int, Tuple[int, int, int, int, int]] = {}
        for i in range(0, len(d) - 1, 2):
            a, b = d[i], d[i + 1]

            def field(line, k):
                s = line[8 * k : 8 * k + 8].strip()
                return int(s) if s else 0

            self.dir[i + 1] = (field(a, 0), field(a, 1), field(b, 3), field(a, 6), field(b, 4))
        self.params = [line[:64] for line in sections.get("P", [])]

    def entry(self, de: int, *types: int) -> Tuple[int, list]:
        """``(type, [parameters after the type])`` of entity ``de`` (of one of ``types``)."""
        if de not in self.dir:
            raise Unsupported(f"DE {de}: no such entry")
        kind, start, count, _, _ = self.dir[de]
        if types and kind not in types:
            raise Unsupported(f"DE {de} is a {kind}, not {' or '.join(map(str, types))}")
        text = "".join(self.params[start - 1 : start - 1 + count])
        fields = self._fields(text)
        return kind, fields[1:]

    def _fields(self, text: str) -> list:
        """The fields of a parameter record: Hollerith strings as text, numbers as floats
        (``D`` exponents too), empty fields as 0."""
        out, i = [], 0
        while i < len(text):
            m = _HOLLERITH.match(text, i)
            if m:  # Hollerith string: its length, then that many characters
                n = int(m.group(1))
                start = i + m.end()
                out.append(text[start : start + n])
                i = start + n
                while i < len(text) and text[i] == " ":
                    i += 1
            else:
                j = i
                while j < len(text) and text[j] not in (self.delim, self.end):
                    j += 1
                s = text[i:j].strip()
                out.append(float(s.replace("D", "E").replace("d", "e")) if s else 0.0)
                i = j
            if i >= len(text) or text[i] == self.end:
                break
            i += 1  # the parameter delimiter
        return out

    def matrix(self, de: int, depth: int = 0) -> np.ndarray:
        """The 3 x 4 matrix placing entity ``de``'s definition space in model space: its 124
        transformation matrix, composed with that matrix's own (IGES 5.3: ``M = M_parent
        M_124``), the identity when the pointer is 0."""
        pointer = self.dir[de][3] if de in self.dir else 0
        if pointer == 0:
            return np.hstack([np.eye(3), np.zeros((3, 1))])
        if depth > 32:
            raise Unsupported(f"DE {de}: transformation chain too deep")
        kind, p = self.entry(pointer, 124)
        if self.dir[pointer][4] not in (0, 1):
            raise Unsupported(f"DE {pointer}: 124 of form {self.dir[pointer][4]}")
        own = np.array(p[:12], float).reshape(3, 4)
        parent = self.matrix(pointer, depth + 1)
        return np.hstack([parent[:, :3] @ own[:, :3], parent[:, :3] @ own[:, 3:] + parent[:, 3:]])

    def curve(self, de: int) -> Callable[[np.ndarray], np.ndarray]:
        """Curve ``de`` in model space (its transformation applied), ``t (n,) -> (n, 3)``:
        110 line ``P1 + t (P2 - P1)``; 100 circular arc ``(X1 + R cos t, Y1 + R sin t, ZT)``,
        ``t`` the angle from the definition space's x axis."""
        kind, p = self.entry(de)
        m = self.matrix(de)
        place = lambda q: q @ m[:, :3].T + m[:, 3]  # noqa: E731
        if kind == 110:
            a, b = np.array(p[0:3], float), np.array(p[3:6], float)
            return lambda t: place(a + t[:, None] * (b - a))
        if kind == 100:
            zt, x1, y1, x2, y2 = map(float, p[:5])
            r = math.hypot(x2 - x1, y2 - y1)
            return lambda t: place(np.column_stack([x1 + r * np.cos(t), y1 + r * np.sin(t), np.full(len(t), zt)]))
        raise Unsupported(f"DE {de}: curve of type {kind}")

    def face_surface(self, de: int) -> Tuple[str, Surface]:
        """``(type, surface)`` of face ``de`` (a 144 trimmed surface, 143 bounded surface or
        510 face), the surface in model space."""
        kind, p = self.entry(de, 144, 143, 510)
        return self.surface(int(p[1] if kind == 143 else p[0]))

    def surface(self, de: int) -> Tuple[str, Surface]:
        """``(type, (u, v) -> points)`` of surface ``de`` in model space, IGES 5.3's
        parameterisation (the reader's for a 108)."""
        kind, p = self.entry(de)
        m = self.matrix(de)
        place = lambda q: q @ m[:, :3].T + m[:, 3]  # noqa: E731
        if kind == 120:
            # IGES 5.3, 4.18: the generatrix C(t) turned about the axis line L (from its start
            # to its end point, right-handed) by the angle theta; (u, v) = (t, theta).
            axis_de, generatrix = int(p[0]), self.curve(int(p[1]))
            self.entry(axis_de, 110)
            ends = self.curve(axis_de)(np.array([0.0, 1.0]))
            origin, axis = ends[0], _unit(ends[1] - ends[0], f"DE {axis_de}")
            return "120", lambda uv: place(rotate(generatrix(uv[:, 0]), origin, axis, uv[:, 1]))
        if kind == 108:
            # Not parametrised by IGES; the reader's axes (crates/rs-io/src/cad/iges/faces.rs):
            # origin the plane's point nearest the world origin, u along the world axis least
            # aligned with the normal (the first of equals) projected onto the plane, v = n x u.
            n = np.array(p[0:3], float)
            d = float(p[3])
            nn = float(n @ n)
            unit = _unit(n, f"DE {de}")
            origin = n * d / nn
            axis = int(np.argmin(np.abs(unit)))
            e1 = _unit(np.eye(3)[axis] - unit * unit[axis], f"DE {de}")
            e2 = np.cross(unit, e1)
            return "108", lambda uv: place(origin + uv[:, :1] * e1 + uv[:, 1:] * e2)
        if kind == 128:
            # IGES 5.3, 4.23: K1, K2, M1, M2, PROP1-5, the knots S(-M1..N1+M1) and
            # T(-M2..N2+M2), the weights and the control points with the first index (along
            # u) running fastest, then U0, U1, V0, V1.
            k1, k2, m1, m2 = (int(x) for x in p[:4])
            nu, nv = k1 + 1, k2 + 1
            at = 9
            ku = np.array(p[at : at + nu + m1 + 1], float)
            at += nu + m1 + 1
            kv = np.array(p[at : at + nv + m2 + 1], float)
            at += nv + m2 + 1
            w = np.array(p[at : at + nu * nv], float).reshape(nv, nu).T
            at += nu * nv
            xyz = np.array(p[at : at + 3 * nu * nv], float).reshape(nv, nu, 3).transpose(1, 0, 2)
            surface = bspline_surface((m1, m2), (ku, kv), xyz, w)
            return "128", lambda uv: place(surface(uv))
        raise Unsupported(f"DE {de}: surface of type {kind}")
