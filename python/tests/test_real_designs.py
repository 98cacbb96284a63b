"""xshell.Linkage on a real design of ../shared/data/elasticrods: the
derivatives against finite differences (test_linkage.py). Skipped, as a
whole file (CTest: python/real_designs), when that folder is absent."""

import pytest

import xshell
from test_linkage import (
    GRADIENT_TOLERANCE,
    HESSIAN_TOLERANCE,
    gradient_errors,
    hessian_errors,
    random_state,
    sample_dict,
)


def test_hyperboloid_derivatives(shared_data):
    """A non-planar design with valence-3 joints (shared data)."""
    cfg = sample_dict(supports=[{"vertex": 0, "fix": ["position", "orientation"]}])
    cfg["linkage"] = str(shared_data / "hyperboloid_open.obj")
    cfg["material"]["young_modulus"] = 1.0e3
    cfg["material"]["cross_section"] = {"shape": "rectangle", "width": 0.05, "height": 0.03}
    cfg["loads"] = {"gravity": [0, 0, -9.81]}
    lk = xshell.Linkage(cfg)
    rng = random_state(lk, 4)
    assert gradient_errors(lk, lk.gradient(), rng).max() < GRADIENT_TOLERANCE
    assert hessian_errors(lk, lk.hessian(), rng).max() < HESSIAN_TOLERANCE
