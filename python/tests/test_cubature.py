"""``inrs.cubature`` and ``Domain.integrate``: the rule's properties (positive weights, at most
``dim P_n`` nodes, every node classified inside, weights adding up to the area), monomials on
the unit disc against closed forms (the Beta function), ``exp(x + y)`` on the unit square,
one-line ``ValueError``s, and equality with ``inrs cubature`` / ``inrs integrate``."""

import math
import subprocess

import numpy as np
import pytest

import inrs

from conftest import FIXTURES

DISC = FIXTURES / "inrs-paper" / "circle.json"
UNIT_SQUARE = '{"curves": [{"polyline": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]}]}'
DOMAINS = [
    FIXTURES / "inrs-paper" / "circle.json",
    FIXTURES / "inrs-paper" / "l_shape.json",
    FIXTURES / "inrs-paper" / "s5_lune.json",
    FIXTURES / "io" / "gear.svg",
]


def unit_disc_moment(p: int, q: int) -> float:
    """``integral over the unit disc of x^p y^q``: ``2 B((p + 1) / 2, (q + 1) / 2) / (p + q +
    2)`` for even ``p``, ``q`` (polar coordinates), 0 otherwise."""
    if p % 2 or q % 2:
        return 0.0
    beta = math.gamma((p + 1) / 2) * math.gamma((q + 1) / 2) / math.gamma((p + q + 2) / 2)
    return 2 * beta / (p + q + 2)


def test_the_closed_form_is_right():
    assert unit_disc_moment(0, 0) == pytest.approx(math.pi, rel=1e-15)
    assert unit_disc_moment(2, 0) == pytest.approx(math.pi / 4, rel=1e-15)
    assert unit_disc_moment(2, 2) == pytest.approx(math.pi / 24, rel=1e-15)


@pytest.mark.parametrize("path", DOMAINS, ids=lambda p: p.name)
def test_rule_is_positive_interior_and_adds_up_to_the_area(path):
    d = inrs.Domain.load(path)
    n = 6
    nodes, weights = inrs.cubature(d, n)
    assert nodes.dtype == weights.dtype == np.float64
    assert nodes.ndim == 2 and nodes.shape[1] == 2 and weights.shape == (len(nodes),)
    assert 0 < len(nodes) <= (n + 1) * (n + 2) // 2
    assert (weights > 0).all()
    assert (d.classify(nodes) == inrs.INSIDE).all()
    area = d.summary().filled_area
    assert weights.sum() == pytest.approx(area, rel=1e-12, abs=0)


def test_monomials_on_the_unit_disc():
    d = inrs.Domain.load(DISC)
    n = 12
    nodes, weights = inrs.cubature(d, n)
    x, y = nodes[:, 0], nodes[:, 1]
    for total in range(n + 1):
        for q in range(total + 1):
            p = total - q
            got = weights @ (x**p * y**q)
            assert abs(got - unit_disc_moment(p, q)) < 1e-13, (p, q, got)
    # Domain.integrate gives the same sums, f called once with the nodes' coordinates.
    calls = []

    def f(xs, ys):
        calls.append((xs.copy(), ys.copy()))
        return xs**2 * ys**2

    assert d.integrate(f, degree=n) == pytest.approx(math.pi / 24, abs=1e-14)
    assert len(calls) == 1
    assert np.array_equal(calls[0][0], x) and np.array_equal(calls[0][1], y)


def test_integrate_exp_on_the_unit_square_and_constants():
    d = inrs.Domain.from_json(UNIT_SQUARE)
    got = d.integrate(lambda x, y: np.exp(x + y))
    assert abs(got - (math.e - 1) ** 2) < 1e-10
    assert d.integrate(lambda x, y: np.exp(x + y), degree=20) == got
    # A low degree is used, and is coarser.
    assert abs(d.integrate(lambda x, y: np.exp(x + y), degree=2) - (math.e - 1) ** 2) > 1e-6
    # A scalar is a constant at every node.
    assert d.integrate(lambda x, y: 2.5, degree=3) == pytest.approx(2.5, rel=1e-14)
    assert d.integrate(lambda x, y: x**3 * y**7 - 5 * x, degree=10) == pytest.approx(1 / 32 - 2.5, abs=1e-14)


def test_bad_input_raises_one_line_value_errors():
    d = inrs.Domain.load(DISC)
    open_domain = inrs.Domain.load(FIXTURES / "bad" / "open_loop.json")
    thin = inrs.Domain.from_json(
        '{"curves": [{"circle": {"center": [0, 0], "radius": 1.000001}},'
        ' {"circle": {"center": [0, 0], "radius": 1}}]}'
    )
    top = inrs.MAX_CUBATURE_DEGREE
    cases = [
        (lambda: inrs.cubature(d, top + 1), f"degree {top + 1} is above the limit {top}"),
        (lambda: inrs.cubature(d, -1), "degree must be an integer >= 0"),
        (lambda: inrs.cubature(d, 2.5), "degree must be an integer"),
        (lambda: inrs.cubature(open_domain, 4), "open boundary"),
        (lambda: open_domain.integrate(lambda x, y: x), "open boundary"),
        (lambda: inrs.cubature(thin, 2), "too thin or too small"),
        (lambda: d.integrate(lambda x, y: x, degree=top + 1), "above the limit"),
        (lambda: d.integrate(lambda x, y: x[:-1], degree=4), r"shape \(14,\) for 15 nodes"),
        (lambda: d.integrate(lambda x, y: np.stack([x, y]), degree=4), "shape"),
        (lambda: d.integrate(lambda x, y: "x", degree=4), "f must return numbers"),
        (lambda: d.integrate(lambda x, y: 1 / (x - x), degree=4), r"integrand value inf at node 0 \("),
    ]
    with np.errstate(divide="ignore", invalid="ignore"):
        for call, message in cases:
            with pytest.raises(ValueError, match=message) as e:
                call()
            assert "\n" not in str(e.value)
        # sqrt(x) is NaN where x < 0: the node named is one of those, and its coordinates
        # are the node's.
        nodes, _ = inrs.cubature(d, 4)
        with pytest.raises(ValueError, match=r"integrand value NaN at node (\d+) \(") as e:
            d.integrate(lambda x, y: np.sqrt(x), degree=4)
    text = str(e.value)
    k = int(text.split("at node ")[1].split(" ")[0])
    x, y = (float(v) for v in text.split("(")[1].split(")")[0].split(","))
    assert (x, y) == tuple(nodes[k]) and x < 0


def test_cubature_and_integrate_equal_the_cli(cli):
    out = subprocess.run(
        [cli, "cubature", "--domain", DISC, "--degree", "10"], check=True, capture_output=True, text=True
    )
    lines = out.stdout.splitlines()
    assert lines[0] == "x,y,w"
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    nodes, weights = inrs.cubature(inrs.Domain.load(DISC), 10)
    # The same library call: the same candidates are chosen as nodes, bit for bit. The weights
    # agree to rounding of the least-squares solve, not to the bit: the `inrs` binary that
    # `cargo test --workspace` builds has a dev-dependency's math feature (num-traits `libm`)
    # unified into nalgebra, which the wheel's build does not (measured: 2.4e-12 relative on the
    # smallest weights, sums equal within 4e-16).
    assert np.array_equal(rows[:, :2], nodes)
    np.testing.assert_allclose(rows[:, 2], weights, rtol=1e-10, atol=0)
    assert "nodes (at most 66)" in out.stderr
    value = subprocess.run(
        [cli, "integrate", "--domain", DISC, "--function", "x^2 * y^4 + 3", "--degree", "10"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    got = inrs.Domain.load(DISC).integrate(lambda x, y: x**2 * y**4 + 3, degree=10)
    assert float(value) == pytest.approx(got, rel=1e-15)
    assert got == pytest.approx(math.pi / 64 + 3 * math.pi, rel=1e-14)
