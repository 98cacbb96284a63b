"""xshell from Python: relax a linkage, read its result as numpy arrays, and
evaluate the model (energy, gradient, Hessian) for research code.

    import xshell
    res = xshell.relax("samples/grid_gravity.json")
    res.status, res.converged, res.stable, res.energy["total"]
    res.vertices          # numpy (V, 3), the OBJ's vertex order
    res.opening_angles    # numpy (V,), nan at free rod ends

The same engine as the command line `xshell relax` (the same code runs the
configuration: app/relax_run.hpp), so that ``res.summary`` is the dict that
summary.json holds. Units are the configuration's (README, "Configuration");
the reduced unknowns of ``Linkage.dofs`` are in the order of docs/model.md
("The reduced unknowns"). See the README, section "Python".
"""

import json
import os

import numpy as np

from . import _core

__all__ = ["relax", "Result", "State", "Linkage", "design", "DesignResult", "__version__"]
__version__ = _core.version


class State:
    """A state of a linkage: the text of a state.json, passable as
    ``relax(..., init=state)`` and ``Linkage(..., init=state)``. A state is
    checked against the linkage when it is used: one of another linkage is
    refused there with ValueError."""

    def __init__(self, text, name="the state"):
        self.text = text
        self.name = name

    def save(self, path):
        """Writes the state as a state.json (the command line's --init)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.text)

    @classmethod
    def load(cls, path):
        """Reads a state.json (written by `xshell relax` or State.save)."""
        with open(path, encoding="utf-8") as f:
            return cls(f.read(), os.fspath(path))

    def __eq__(self, other):
        return isinstance(other, State) and self.text == other.text

    def __repr__(self):
        return "<xshell.State of %s (%d characters)>" % (self.name, len(self.text))


class Result:
    """What a relax run found: the fields of summary.json, with arrays as
    numpy arrays.

    status, reason       summary.json's status ("converged", "max_iterations",
                         "interrupted", ...) and its one-line reason
    converged, stable    booleans; stable is None when the run did not converge
    iterations           Newton iterations, dynamics steps or kinetic-damping iterations
    energy               dict: total, stretching, bending, twisting, external
    vertices             numpy float64 (V, 3): per graph vertex in OBJ order
    opening_angles       numpy float64 (V,), radians, nan at free rod ends
    summary              the dict that summary.json holds
    state                the final State (init= of a later run)
    exit_status          the command line's exit status for this run (0 converged,
                         3 not converged, 130 interrupted)
    """

    def __init__(self, summary, state, exit_status):
        self.summary = summary
        self.state = state
        self.exit_status = exit_status

    status = property(lambda self: self.summary["status"])
    reason = property(lambda self: self.summary["reason"])
    converged = property(lambda self: self.summary["converged"])
    stable = property(lambda self: self.summary["stable"])
    iterations = property(lambda self: self.summary["iterations"])
    energy = property(lambda self: dict(self.summary["energy"]))

    @property
    def vertices(self):
        return np.array(self.summary["vertices"], dtype=np.float64).reshape(-1, 3)

    @property
    def opening_angles(self):
        return np.array(
            [np.nan if a is None else a for a in self.summary["opening_angles"]], dtype=np.float64
        )

    def __repr__(self):
        return "<xshell.Result %s after %d iterations: energy %.10e>" % (
            self.status,
            self.iterations,
            self.energy["total"],
        )


def _configuration(config):
    """(name or path, JSON text or None, base folder) of a configuration
    given as a path or as a dict of its keys (relative paths in a dict are
    relative to the working directory)."""
    if isinstance(config, dict):
        try:
            text = json.dumps(config, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise ValueError("<dict>: not a JSON configuration: %s" % e) from None
        return "<dict>", text, os.getcwd()
    if isinstance(config, (str, os.PathLike)):
        return os.fspath(config), None, ""
    raise TypeError("config: a path or a dict, not %s" % type(config).__name__)


def _initial_state(init):
    """(name or path, text or None) of init: None, a State or a path."""
    if init is None:
        return None, None
    if isinstance(init, State):
        return init.name, init.text
    if isinstance(init, (str, os.PathLike)):
        return os.fspath(init), None
    raise TypeError("init: a State, a path or None, not %s" % type(init).__name__)


def _run(config, solver, write_files, out, init, progress, lines="off", log=False):
    name, text, base = _configuration(config)
    init_name, init_text = _initial_state(init)
    if out is not None:
        out = os.fspath(out)
    return _core.relax(
        name, text, base, solver, write_files, out, init_name, init_text, progress, lines, log
    )


def relax(config, solver=None, init=None, out=None, progress=None):
    """Relaxes a linkage to its static equilibrium, as `xshell relax` does.

    config    a configuration file's path, or a dict with its keys (relative
              paths then relative to the working directory)
    solver    "newton", "dynamics" or "kinetic-damping" (overrides solver.method)
    init      a State (Result.state, State.load) or a state.json path to start from
    out       None: no file is written; a folder: the command line's outputs
              (summary.json, state.json, the VTK series, ...) go there
    progress  a callable receiving one dict per iteration (per history record:
              iteration, time, energy, gradient_norm, step, kinetic_energy, seconds)

    Returns a Result; a solve that fails (not converged, a failed line
    search, ...) is a Result whose status says so. Raises ValueError with
    the command line's message for an invalid input (configuration, linkage,
    state), OSError when an output cannot be written. Ctrl-C
    (KeyboardInterrupt) stops the solve at its next iteration; with `out`,
    the outputs of an interrupted run are written (status "interrupted"),
    then KeyboardInterrupt is raised. An exception of `progress` stops the
    solve the same way and is raised. The GIL is released while the solve
    runs: threads solve in parallel.
    """
    status, error, summary, state = _run(config, solver, out is not None, out, init, progress)
    if status == _core.EXIT_INVALID_INPUT:
        raise ValueError(error)
    if status == _core.EXIT_OUTPUT_FAILED:
        raise OSError(error)
    return Result(json.loads(summary), State(state, "the state of a run"), status)


class DesignResult:
    """What a design run found: the fields of design.json.

    status, reason       "converged", "max_iterations", "interrupted" or "failed",
                         and IPOPT's reason
    rest_lengths         numpy float64 (segments,): the design, per OBJ edge
    fit                  dict: max and rms distance of the targeted joints to
                         their targets (length), targets (their count)
    history              list of dicts, one per design iteration (design.json's)
    iterations           design iterations
    report               the dict that design.json holds
    deployed_state       the optimized design's deployed State
    flat_state           its flat State
    exit_status          the command line's exit status (0 converged, 3 not, 130 interrupted)
    """

    def __init__(self, report, deployed_state, flat_state, exit_status):
        self.report = report
        self.deployed_state = deployed_state
        self.flat_state = flat_state
        self.exit_status = exit_status

    status = property(lambda self: self.report["status"])
    reason = property(lambda self: self.report["reason"])
    fit = property(lambda self: dict(self.report["fit"]))
    history = property(lambda self: list(self.report["history"]))
    iterations = property(lambda self: self.report["iterations"])

    @property
    def rest_lengths(self):
        return np.array(self.report["rest_lengths"], dtype=np.float64)

    def __repr__(self):
        return "<xshell.DesignResult %s after %d iterations: fit rms %.3e, max %.3e>" % (
            self.status,
            self.iterations,
            self.report["fit"]["rms"],
            self.report["fit"]["max"],
        )


def design(config, init=None, out=None, progress=None):
    """Finds the rest lengths whose deployed shell fits the configuration's
    "design" target, as `xshell design` does (README, "Design").

    config    a configuration file's path, or a dict with its keys (with a
              "design" section)
    init      a State or a state.json path of the flat linkage to start from
    out       None: no file is written; a folder: the command line's outputs
              (design.json, deployed_state.json, flat_state.json, the VTK
              series, flat_layout.obj, fabrication data) go there
    progress  a callable receiving one dict per design iteration (an element
              of design.json's history)

    Returns a DesignResult (an optimization that stopped at its iteration
    limit is one too: its status says so). Raises ValueError with the
    command line's message for an invalid input, RuntimeError when the start
    cannot be deployed, OSError when an output cannot be written. Ctrl-C
    stops at the next design iteration (the best design so far reported and
    written), then raises KeyboardInterrupt.
    """
    name, text, base = _configuration(config)
    init_name, init_text = _initial_state(init)
    status, error, report, deployed, flat = _core.design(
        name,
        text,
        base,
        out is not None,
        None if out is None else os.fspath(out),
        init_name,
        init_text,
        progress,
    )
    if status == _core.EXIT_INVALID_INPUT:
        raise ValueError(error)
    if status == _core.EXIT_OUTPUT_FAILED:
        raise OSError(error)
    if report is None:
        raise RuntimeError(error)
    return DesignResult(
        json.loads(report),
        State(deployed, "the deployed state of a design"),
        State(flat, "the flat state of a design"),
        status,
    )


class Linkage:
    """The statics problem of a configuration, for research code: its
    linkage, supports and loads, as `relax` would solve it.

    dofs          numpy (n,): every reduced unknown, in the documented order
                  (docs/model.md, "The reduced unknowns"), fixed ones included
    set_dofs(q)   moves the linkage to the unknowns q (n,)
    energy()      the total energy: elastic energy minus the work of the dead loads
    energy_terms() dict: total, stretching, bending, twisting, external
    gradient()    numpy (n,): its gradient over every unknown
    hessian()     scipy.sparse.csc_matrix (n, n): the full symmetric Hessian
    free          numpy bool (n,): the unknowns that no support holds
    update_frames() the solvers' frame update: the rods' reference (source)
                  frames moved to the current state and the joints' rotations
                  folded (dofs change; the configuration does not)
    vertices, opening_angles, state   as in a Result
    length_scale  the diagonal of the input's bounding box
    """

    def __init__(self, config, init=None):
        name, text, base = _configuration(config)
        init_name, init_text = _initial_state(init)
        self._core = _core.Linkage(name, text, base, init_name, init_text)

    @property
    def dofs(self):
        return np.array(self._core.dofs, dtype=np.float64)

    def set_dofs(self, q):
        self._core.set_dofs(np.ascontiguousarray(q, dtype=np.float64))

    def energy(self):
        return self._core.energy()

    def energy_terms(self):
        return self._core.energy_terms()

    def gradient(self):
        return np.array(self._core.gradient(), dtype=np.float64)

    def hessian(self):
        import scipy.sparse

        return scipy.sparse.csc_matrix(self._core.hessian())

    @property
    def free(self):
        return np.array(self._core.free, dtype=bool)

    def update_frames(self):
        self._core.update_frames()

    @property
    def vertices(self):
        return np.array(self._core.vertices, dtype=np.float64)

    @property
    def opening_angles(self):
        return np.array(self._core.opening_angles, dtype=np.float64)

    @property
    def state(self):
        return State(self._core.state, "the state of a Linkage")

    @property
    def length_scale(self):
        """The diagonal of the input's bounding box (a length)."""
        return self._core.length_scale
