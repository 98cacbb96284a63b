"""xshell.Linkage: the model's derivatives against finite differences, at a
random state right after a frame update (the solvers' update_frames)."""

import json

import numpy as np
import pytest
import scipy.sparse

import xshell
from conftest import SAMPLES

H = 1e-6  # central-difference step, relative to the linkage's size
GRADIENT_TOLERANCE = 1e-6  # relative error of a directional derivative
HESSIAN_TOLERANCE = 1e-6


def sample_dict(**changes):
    with open(SAMPLES / "grid_gravity.json") as f:
        cfg = json.load(f)
    cfg["linkage"] = str(SAMPLES / cfg["linkage"])
    cfg.update(changes)
    return cfg


def random_state(lk, seed):
    """Moves lk to a random state near its input, then updates its frames.
    Returns the generator for the directions."""
    rng = np.random.default_rng(seed)
    q = lk.dofs
    lk.set_dofs(q + 1e-3 * lk.length_scale * rng.standard_normal(q.size))
    lk.update_frames()
    return rng


def directions(rng, n, count):
    d = rng.standard_normal((count, n))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def central_difference(lk, f, d):
    """(f(q + h d) - f(q - h d)) / 2h at the linkage's unknowns q, with h
    relative to its size; the linkage is left at q."""
    q = lk.dofs
    h = H * lk.length_scale
    lk.set_dofs(q + h * d)
    plus = f()
    lk.set_dofs(q - h * d)
    minus = f()
    lk.set_dofs(q)
    return (plus - minus) / (2 * h)


def gradient_errors(lk, gradient, rng, count=8):
    """Relative errors of gradient . d against central differences of the
    energy along random unit directions d."""
    errors = []
    for d in directions(rng, lk.dofs.size, count):
        fd = central_difference(lk, lk.energy, d)
        errors.append(abs(fd - gradient @ d) / np.linalg.norm(gradient))
    return np.array(errors)


def hessian_errors(lk, hessian, rng, count=8):
    """Relative errors of hessian @ d against central differences of the
    gradient along random unit directions d."""
    errors = []
    for d in directions(rng, lk.dofs.size, count):
        fd = central_difference(lk, lk.gradient, d)
        hd = hessian @ d
        errors.append(np.linalg.norm(fd - hd) / np.linalg.norm(hd))
    return np.array(errors)


def soft_sample():
    """The sample 2e6 times softer: the dead loads' part of the Hessian
    (through the terminal edges of rotation joints) is then large enough
    for the check to see it."""
    cfg = sample_dict()
    cfg["material"]["young_modulus"] = 1.0e4
    return cfg


CONFIGS = {
    "rotation joints": lambda: sample_dict(),
    "edge-vector joints": lambda: sample_dict(joints="edge_vectors"),
    "rotation joints, soft": soft_sample,
}


@pytest.fixture(params=sorted(CONFIGS))
def linkage(request):
    return xshell.Linkage(CONFIGS[request.param]())


def test_shapes_and_types(linkage):
    n = linkage.dofs.size
    assert linkage.dofs.dtype == np.float64 and linkage.dofs.shape == (n,)
    assert linkage.gradient().shape == (n,)
    h = linkage.hessian()
    assert isinstance(h, scipy.sparse.csc_matrix) and h.shape == (n, n)
    assert linkage.free.dtype == bool and linkage.free.shape == (n,)
    # The sample's four supports hold three position components each.
    assert n - linkage.free.sum() == 12
    summary = xshell.relax(SAMPLES / "grid_gravity.json").summary
    if linkage.dofs.size == summary["unknowns"]:
        assert linkage.free.sum() == summary["free_unknowns"]


@pytest.mark.parametrize("seed", [1, 2])
def test_gradient_matches_energy_differences(linkage, seed):
    rng = random_state(linkage, seed)
    errors = gradient_errors(linkage, linkage.gradient(), rng)
    assert errors.size == 8
    assert errors.max() < GRADIENT_TOLERANCE, errors


@pytest.mark.parametrize("seed", [1, 2])
def test_hessian_matches_gradient_differences(linkage, seed):
    rng = random_state(linkage, seed)
    hessian = linkage.hessian()
    errors = hessian_errors(linkage, hessian, rng)
    assert errors.size == 8
    assert errors.max() < HESSIAN_TOLERANCE, errors
    asymmetry = scipy.sparse.linalg.norm(hessian - hessian.T) / scipy.sparse.linalg.norm(hessian)
    assert asymmetry < 1e-12


def test_the_checks_can_fail(linkage):
    """The same checks reject a gradient and a Hessian wrong by 0.1 %: they
    do not pass whatever they are given."""
    rng = random_state(linkage, 3)
    gradient = linkage.gradient()
    wrong_gradient = gradient + 1e-3 * np.linalg.norm(gradient) * rng.standard_normal(gradient.size)
    assert gradient_errors(linkage, wrong_gradient, rng).max() > 10 * GRADIENT_TOLERANCE
    hessian = linkage.hessian()
    assert hessian_errors(linkage, hessian * (1 + 1e-3), rng).max() > 10 * HESSIAN_TOLERANCE


def test_set_dofs_moves_the_linkage(linkage):
    q = linkage.dofs
    before = linkage.vertices
    e0 = linkage.energy()
    linkage.set_dofs(q + 1e-3 * linkage.length_scale)
    assert linkage.energy() != e0
    assert not np.array_equal(linkage.vertices, before)
    linkage.set_dofs(q)
    assert linkage.energy() == e0
    with pytest.raises(ValueError, match="expected"):
        linkage.set_dofs(q[:-1])


def test_gradient_vanishes_at_the_equilibrium_on_the_free_unknowns():
    res = xshell.relax(SAMPLES / "grid_gravity.json")
    lk = xshell.Linkage(SAMPLES / "grid_gravity.json", init=res.state)
    g = lk.gradient()
    assert lk.energy() == pytest.approx(res.energy["total"], rel=1e-12)
    assert np.abs(g[lk.free]).max() < 1e-6 * np.abs(g[~lk.free]).max()

