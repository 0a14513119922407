"""The C++ broad-phase contact search (_cpp.find_candidates) equals a numpy
brute force, and refuses bad shapes with a message naming the argument."""
import re

import numpy as np
import pytest

from hypercontact import _cpp


def brute_force(slave_x, master_x, facets, capture):
    """Every (point, facet) pair: is the point in the facet's box inflated by capture?"""
    nodes = master_x[facets]                      # (f, k, 3)
    lo = nodes.min(axis=1) - capture
    hi = nodes.max(axis=1) + capture
    x = slave_x[:, None, :]
    inside = np.all((lo <= x) & (x <= hi), axis=2)  # (n, f)
    offsets = np.concatenate([[0], np.cumsum(inside.sum(axis=1))])
    return offsets, np.nonzero(inside)[1]         # row-major: each list ascending


def wavy_quads(n, rng):
    """(n+1)² nodes of a randomly warped sheet and its n² quadrilaterals."""
    u, v = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    z = 0.1 * np.sin(2 * np.pi * rng.random() + 5 * u) * np.cos(4 * v)
    x = np.column_stack([u.ravel(), v.ravel(), z.ravel()])
    a = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    quads = np.column_stack([a, a + 1, a + n + 2, a + n + 1]).astype(np.int32)
    return x, quads


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_matches_numpy_brute_force(seed):
    rng = np.random.default_rng(seed)
    master_x, quads = wavy_quads(12, rng)
    # Slave points on and near the sheet, and random ones around it.
    near = master_x[rng.integers(0, len(master_x), 300)] + rng.normal(0, 0.03, (300, 3))
    around = rng.uniform([-0.3, -0.3, -0.5], [1.3, 1.3, 0.5], (200, 3))
    slave_x = np.vstack([master_x, near, around])
    triangles = np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    for facets in (quads, triangles):
        for capture in (0.0, 0.01, 0.2):
            offsets, indices = _cpp.find_candidates(slave_x, master_x, facets, capture)
            assert offsets.dtype == np.int32 and indices.dtype == np.int32
            expected_offsets, expected_indices = brute_force(slave_x, master_x, facets, capture)
            np.testing.assert_array_equal(offsets, expected_offsets)
            np.testing.assert_array_equal(indices, expected_indices)
            reference = _cpp.find_candidates_brute_force(slave_x, master_x, facets, capture)
            np.testing.assert_array_equal(reference[0], expected_offsets)
            np.testing.assert_array_equal(reference[1], expected_indices)
            counts = np.diff(offsets)
            assert (counts[:len(master_x)] > 0).all()  # a node lies in its facets' boxes
            assert (counts == 0).sum() > 20            # some points are out of reach


def test_empty_inputs():
    offsets, indices = _cpp.find_candidates(np.zeros((0, 3)), np.zeros((0, 3)),
                                            np.zeros((0, 4), np.int32), 0.5)
    assert offsets.tolist() == [0] and indices.size == 0


def test_bad_input_is_named():
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    quad = np.array([[0, 1, 2, 3]], np.int32)
    with pytest.raises(ValueError, match=re.escape("slave_x: expected shape (*, 3), got (5, 2)")):
        _cpp.find_candidates(np.zeros((5, 2)), x, quad, 0.1)
    with pytest.raises(ValueError, match=re.escape("master_x: expected shape (*, 3), got (12,)")):
        _cpp.find_candidates(np.zeros((5, 3)), x.ravel(), quad, 0.1)
    with pytest.raises(ValueError, match=re.escape(
            "facets: expected shape (*, 3), (*, 4), (*, 6) or (*, 9), got (1, 5)")):
        _cpp.find_candidates(np.zeros((5, 3)), x, np.array([[0, 1, 2, 3, 0]], np.int32), 0.1)
    with pytest.raises(IndexError, match=re.escape("facets[0, 2] = 4 is not a master node index")):
        _cpp.find_candidates(np.zeros((5, 3)), x, np.array([[0, 1, 4, 3]], np.int32), 0.1)
    with pytest.raises(ValueError, match="capture = -0.1, expected a finite distance"):
        _cpp.find_candidates(np.zeros((5, 3)), x, quad, -0.1)
    with pytest.raises(TypeError):  # int64 indices are refused, never silently truncated
        _cpp.find_candidates(np.zeros((5, 3)), x, quad.astype(np.int64), 0.1)
