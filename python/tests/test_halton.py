"""The Halton generator behind the papers' test clouds: exact values, blocks, errors."""

from fractions import Fraction

import numpy as np
import pytest

import inrs


def radical_inverse(i: int, base: int) -> Fraction:
    """Exact radical inverse: the base-``base`` digits of ``i`` mirrored about the point."""
    value, scale = Fraction(0), Fraction(1, base)
    while i > 0:
        i, digit = divmod(i, base)
        value += digit * scale
        scale /= base
    return value


def test_values_match_exact_radical_inverses():
    pts = inrs.halton_points(200, (0.0, 0.0, 1.0, 1.0))
    assert pts.shape == (200, 2) and pts.dtype == np.float64
    for i in range(200):
        assert pts[i, 0] == pytest.approx(float(radical_inverse(i, 2)), abs=1e-15)
        assert pts[i, 1] == pytest.approx(float(radical_inverse(i, 3)), abs=1e-15)
    # Mapped to a box: (xmin + h2 (xmax - xmin), ymin + h3 (ymax - ymin)).
    b = inrs.halton_points(5, (-2.0, 1.0, 2.0, 4.0))
    assert np.allclose(b, [[-2, 1], [0, 2], [-1, 3], [1, 4 / 3], [-1.5, 7 / 3]])


def test_blocks_with_start_are_slices_of_one_sequence():
    box = (-1.0, -0.5, 3.0, 2.0)
    whole = inrs.halton_points(1000, box)
    parts = [inrs.halton_points(n, box, start=s) for s, n in [(0, 300), (300, 1), (301, 699)]]
    assert np.array_equal(np.concatenate(parts), whole)


@pytest.mark.parametrize(
    "n, bounds, start, message",
    [
        (-1, (0, 0, 1, 1), 0, "non-negative"),
        (10, (0, 0, 1, 1), -5, "non-negative"),
        (2**31, (0, 0, 1, 1), 0, "in blocks"),
        (10, (0, 0, 1, 1), 2**64 - 3, "overflows"),
        (10, (1, 0, 0, 1), 0, "xmin <= xmax"),
        (10, (0, 0, float("nan"), 1), 0, "finite"),
    ],
)
def test_bad_arguments_are_value_errors(n, bounds, start, message):
    with pytest.raises(ValueError, match=message):
        inrs.halton_points(n, bounds, start=start)
