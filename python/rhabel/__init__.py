"""rhabel: generalized Abel integral equations, Riemann-Hilbert problems, and rigid indentors
sliding over a power-law viscoelastic half-space (relaxation modulus E(t) = E1 t^-alpha).

The Python face of the C++ library (python/README.md). Everything numerical runs in C++
(the compiled extension rhabel._rhabel); this package validates input and documents.

Contents
    solve(scene, ...)           contact of rigid indentors (rhabel::punch::solve)
    sweep(sweep, ...)           the rows of a sweep of scenes, as `rhabel sweep` (threads, resumable file)
    fit_material(curve, ...)    the local power law of a master curve at U/L, as `rhabel fit-material`
    trial_interval(scene, a, b) the field of a prescribed contact interval (paper Section 4;
                                rhabel::punch::trial_interval)
    validate_scene(scene)       the validation of solve() alone
    load_scene(path)            read a scene JSON file (duplicate keys rejected, as the CLI)
    Record                      the result type: a dict whose keys are also attributes
    Result                      the Record of solve(): repr one line per contact, to_dict()
    Contact                     the Record of one contact: pressure_at(x), the solved pressure
    gauss_jacobi(n, p, q, ...)  Gauss-Jacobi rule (rhabel::quadrature::gauss_jacobi)
    jacobi_p(n, p, q, x)        Jacobi polynomials, vectorised over x
    rhabel.abel                 spectral solver of the generalized Abel equation
    rhabel.riemann              the Riemann-Hilbert route to the same equation

Errors: bad input raises ValueError with a one-line message naming the parameter or field, its
value and the valid range (the library's std::invalid_argument and std::domain_error);
std::overflow_error becomes OverflowError. Long computations release the GIL, so threads can
solve scenes in parallel.
"""

import json as _json
import math as _math
import os as _os
from collections import namedtuple as _namedtuple

from . import _rhabel
from ._record import Contact, Record, Result
from ._scene import json_text as _json_text
from . import abel, riemann

__version__ = _rhabel.__version__

__all__ = ["solve", "sweep", "fit_material", "trial_interval", "load_scene", "validate_scene", "Record", "Result", "Contact", "gauss_jacobi", "GaussJacobiRule",
           "jacobi_p", "abel", "riemann", "__version__"]


def solve(scene, grid=0, displacement=True, tolerance=1e-12, residual=True, acceptance=None, threads=1, time_limit=0,
          layered_below=3e-3, spacing="uniform", profile_knots=False):
    """Solve a scene: rigid indentors sliding together at speed U towards -x over a power-law
    viscoelastic half-space E(t) = E1 t^-alpha (plane strain, steady state). Same schema, same
    validation and same numbers as the command line's ``rhabel solve SCENE.json``: the same code.

    Parameters
    ----------
    scene : dict
        The JSON scene schema (any consistent units; SI: m, Pa, Pa s^alpha, m/s, N/m)::

            {"description": "optional free text",
             "material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.5, "coulomb": 0.0,
                          "name": "optional"},
             "speed": 0.01,
             "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0,
                            "apex": 0.0, "name": "optional"}]}

        ==========================  ==============  ============================================
        field                       valid range     meaning
        ==========================  ==============  ============================================
        material.alpha              [0, 1)          exponent of E(t) = E1 t^-alpha (0: elastic)
        material.E1                 (0, inf)        modulus coefficient [Pa s^alpha]
        material.nu                 [0, 0.5]        Poisson ratio (0.5: beta = 0 whatever coulomb)
        material.coulomb            [0, inf)        Coulomb friction coefficient k
        speed                       (0, inf)        sliding speed U; indentors move towards -x
        indentors                   non-empty list  indentors sliding together
        indentors[i].shape          "parabolic", "wedge" or "flat"
        indentors[i].load           (0, inf)        normal force per unit length [N/m] (not with a body)
        indentors[i].apex           finite, def. 0  parabola vertex, wedge tip, flat face centre
        body.load                   (0, inf)        optional: all indentors on one rigid body with
                                                    this total load; the loads are then unknowns
        indentors[i].height         finite, def. 0  with a body only: apex height on it [m], upward
        indentors[i].radius         (0, inf)        parabolic only: f = -(x - apex)^2 / (2 R)
        indentors[i].slope_leading  (0, inf)        wedge only: slope of the face at x < apex
        indentors[i].slope_trailing (0, inf)        wedge only: slope of the face at x > apex
        indentors[i].width          (0, inf)        flat only: width of the face
        ==========================  ==============  ============================================

        Instead of ``indentors``, with a ``body``: ``"profile": {"x": [...], "z": [...]}`` (or
        ``{"file": "FILE.csv"}``, two columns x,z, relative to the working directory, or to the
        scene file's directory with load_scene) and optional ``"corners"``: a sampled rigid
        profile whose contacts are found.
        Optional ``"period"`` (> 0: the profile repeats, samples in [x_0, x_0 + period), the load
        is per period) and ``"solver"``: ``"spectral"`` (the contact search with Jacobi series
        per contact, finite or periodic; the default without a period) or
        ``"boundary_element"`` (finite or periodic; the default with a period), and for
        the latter ``"max_panels"`` (the finest grid, 256 .. 8388608, ~130 bytes a panel; default
        2^21).

        Instead of ``alpha`` and ``E1`` the material may name a measured master curve:
        ``"material": {"master_curve": "FILE.csv", "temperature": 40, "wlf": {"C1": 8.86,
        "C2": 101.6, "T_ref": 20}, "nu": 0.5, "coulomb": 0.3}`` (``temperature`` and ``wlf``
        together or not at all; the path relative to the working directory, or to the scene
        file's directory with load_scene). The scene is then solved with the power law fitted at
        the contact frequency U/L, iterated to a fixed point (omega0 = U/L with L the contact
        length, or the load-weighted patch width of a profile), by the command line's own code:
        the result gains
        ``material_fit`` (alpha, E1, omega0, the fit's evidence, its ``status``) and its ``scene``
        echoes the fitted alpha and E1.

        Every field is required except ``apex``, ``name``, ``description``, ``body`` and
        ``height`` (with a body an indentor has no ``load``; flat punches on a body are not
        supported); unknown fields are
        errors (also a field of another shape, e.g. ``radius`` on a wedge); numbers must be
        finite ints or floats (NumPy scalars too), not booleans or strings.
    grid : int
        0 (default): no sampled fields. N >= 2: each indentor also gets ``pressure`` (N points
        strictly inside its contact) and ``displacement`` (N points on [a - L, b + L], relative
        to its value at the leading edge a); several contacts also give ``surface`` {``x``,
        ``w``}: the whole surface on one grid (N points a contact over the contacts' span widened
        by the longest contact on either side), in the datum of the contacts' ``approach`` (w =
        f_i + approach_i on contact i), so that the contacts' displacements join into one curve.
        Whatever the grid, each contact's ``pressure_at(x)`` evaluates the solved pressure at any
        points.
    displacement : bool
        With grid > 0, also the displacement samples and the surface (the costlier fields).
    spacing : "uniform" or "graded"
        Where the N pressure samples lie: midpoints of N equal cells (default), or Chebyshev
        points a + L (1 - cos(pi (k + 1/2)/N))/2, dense next to the edges where the pressure
        vanishes or blows up like a power of the distance (``--grid-spacing`` of the command
        line).
    tolerance : float in (0, 1)
        Relative tolerance of the root finders and expansions (default 1e-12).
    residual : bool
        Compute the independent residual of the Abel equation (the evidence that the density
        solves it). False skips it (a quarter to a third of a wedge solve); residuals are None.
    acceptance : float in [1e-15, 0.1] or None
        The bar of status "ok" (residual, negative pressure, load defect, error estimate;
        default None: 1e-9, and 1e-4 for ``profile.solver = "boundary_element"``, a first-order
        method). A sampled profile is worth ~1e-6 (its spline limits the residual).
    threads : int in [0, 1024]
        Threads for the finite-difference Jacobian of several contacts (default 1; 0: every
        core). The result is the same for any count, bit for bit.
    time_limit : float >= 0
        Seconds after which a solve of several contacts (or a sampled profile's contact search)
        stops and returns what it reached with status "not_converged" and a message naming the
        limit (default 0: no limit). A result stopped by it depends on the machine's speed.
        Ctrl-C stops such a solve (KeyboardInterrupt, no result) within about a tenth of a
        second, or, for contacts nearly touching, after the one contact's projection under way
        (up to ~1 s); a one-contact solve takes milliseconds and is not interrupted.
    layered_below : float >= 0
        Several contacts, fewer than six: neighbours closer than this fraction of the shorter
        contact (default 3e-3) have their coupling solved with poles clustered beyond the facing
        ends (a boundary-layer basis), whose cost grows like log(L/gap) instead of the Jacobi
        series' sqrt(L/gap). 0: never; 1: for every pair closer than a contact length. The
        reported density is a Jacobi series either way.
    profile_knots : bool
        A sampled profile solved by the spectral search: build the spline's knots inside each
        contact (where its third derivative jumps) into the density as singular terms of their
        own, instead of resolving them by the series' degree (``--profile-knots`` of the command
        line; default False). The residual of (8) falls from ~4e-7 to ~1e-8 on self-affine
        profiles of 4000 to 16000 samples in about the same time; it is slower where the series
        alone would climb to degree 2048, and not yet ``ok`` within minutes on 1e5 samples.
        Ignored elsewhere.

    Returns
    -------
    Result
        A Record (a dict whose keys are also attributes) with the fields of the JSON result;
        its repr is a summary, one line per contact (interval, load, C_f, status):

        - ``beta``, ``kappa``: friction parameter, tan(beta pi/2) = k (1-2nu)/(2(1-nu)), and
          kappa = cos((alpha + beta/2) pi)/cos(beta pi/2).
        - ``regime``: "below", "boundary" or "above" (sign of alpha + beta/2 - 1/2).
        - ``effective_modulus``: E_U = E1 Gamma(1-alpha) U^alpha/(1-nu^2) [Pa].
        - ``body_approach`` (with a body): approach + height, the same for every indentor [m].
        - ``indentors``: one Record per indentor, in scene order: ``shape``, ``name`` (if
          given), ``contact`` (a, b) with a the leading edge, ``contact_length`` L = b - a,
          ``epsilon`` = (apex - a)/L (wedges only), ``load`` (int p dx, recomputed from the
          solution), ``hysteretic_friction`` C_f, ``total_friction`` C_f + k,
          ``peak_pressure`` (None when the pressure is unbounded, then
          ``peak_pressure_singular`` is True), ``peak_pressure_at``, ``edges`` (two Records:
          ``side``, ``at``, ``singular``, ``exponent``, ``intensity_factor``: p ~ K d^exponent),
          ``residual`` (relative residual of the Abel equation, an estimate), ``error_estimate``
          (an estimate, not a bound), ``approach`` (several indentors: the rigid approach w - f
          on the contact [m], w the surface displacement of the kernel's closed-form integral,
          whose constant a plane-strain half-space leaves free: differences between contacts are
          meaningful),
          ``degree``, ``status`` ("ok", "not_converged", "tension", "load_mismatch",
          "contacts_merge", "penetration" or "contact_lost": "ok" only when the residual, the sign of the
          pressure, the load and the error estimate pass the acceptance 1e-9),
          ``status_message`` (the numbers behind a non-ok status, or a note);
          with grid > 0 ``pressure`` {``x``, ``p``} and ``displacement`` {``x``, ``w``} as NumPy
          arrays (w: downward displacement relative to the leading edge, = f(x) - f(a) in contact).
          Each contact is a ``Contact`` record: ``pressure_at(x)`` evaluates its solved pressure
          at any points (a float or an array in, the same out).
        - ``surface`` {``x``, ``w``} (several contacts, grid > 0, displacement): the whole
          surface displacement on one grid, in the datum of ``approach``.
        - ``diagnostics``: ``residual`` (max over indentors), ``seconds`` (wall time of the
          solve), ``iterations`` (Newton iterations of the coupled solve), ``status`` (the
          worst of the indentors' and the coupled solve's), ``status_message``.
        - ``scene``: the validated scene, defaults filled in.
        - With a profile: ``contacts`` instead of ``indentors`` (each with its ``tip``, the
          highest sample inside it, and the fields above but ``shape``/``name``), ``surface``,
          ``clearance``
          {``min``, ``at``} (the smallest gap between surface and profile at the samples outside
          the contacts and between neighbouring ones where the spline rises above both,
          relative to max z - min z), ``level_mismatch`` {``max``, ``at``} (the
          largest mismatch of neighbouring contacts' levels on the rigid body, relative to
          max z - min z), ``penetrations`` (where the profile
          penetrates the surface outside the contacts found: the contacts a result that is not
          ok is missing), ``hysteretic_friction`` and ``total_friction`` of the body (C_f: the
          contacts' load-weighted mean), ``mean_pressure`` (load per window or period length),
          ``contact_fraction``, with a period ``window`` [x_c, x_c + period] (the period in
          whose abscissae the contacts are reported: it starts in the widest gap),
          ``diagnostics.rounds`` and ``diagnostics.load_fraction`` (the fraction
          of the body's load the contacts carry; below 1 only with a status that is not ok).
        - With ``profile.solver = "boundary_element"``: ``patches`` (each ``contact`` (a, b),
          ``edge_error`` (one panel), ``load`` and ``hysteretic_friction`` as {``value``,
          ``error``}: extrapolated over the last three grids with an error estimate, not a bound;
          ``peak_pressure``, a panel mean), ``hysteretic_friction`` and ``contact_fraction`` of
          the body {``value``, ``error``}, ``total_friction``, ``mean_pressure`` (load per window
          or period length), ``diagnostics`` {``seconds``, ``panels``, ``active_set_steps``,
          ``level_panels``, ``level_patches``, ``level_friction``, ``status``,
          ``status_message``}. "ok" when the C_f estimate is within acceptance x max |z'| and
          every patch load's within acceptance x load (use 1e-3 .. 1e-5: a first-order method).

        ``result.to_dict()`` is the same as plain dicts and lists with the NumPy arrays;
        ``result.to_plain()`` / ``result.to_json()`` give the command line's document.

    Raises
    ------
    ValueError
        Invalid scene (one line naming the field, e.g. ``indentors[0].radius = -2 is outside
        the valid range (0, inf) (radius of curvature of the parabola)``), overlapping
        contacts, no contact interval, or a sampled profile whose contacts would reach the end
        of its samples (the library's message).

    The solve releases the GIL: several threads may solve scenes at the same time.

    Example
    -------
    >>> r = rhabel.solve({"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0},
    ...                   "speed": 0.01,
    ...                   "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100}]})
    >>> r.indentors[0].contact, r.indentors[0].hysteretic_friction
    """
    grid = _grid(grid)
    if acceptance is not None:
        acceptance = float(acceptance)
        if not 1e-15 <= acceptance <= 0.1:
            raise ValueError(f"acceptance = {acceptance!r} is outside the valid range [1e-15, 0.1]")
    if isinstance(threads, bool) or not isinstance(threads, int) or not 0 <= threads <= 1024:
        raise ValueError(f"threads = {threads!r} must be an integer in [0, 1024] (0: every core)")
    time_limit = float(time_limit)
    if not (time_limit >= 0 and time_limit < float("inf")):
        raise ValueError(f"time_limit = {time_limit!r} must be finite and >= 0 (0: no limit)")
    layered_below = float(layered_below)
    if not (layered_below >= 0 and layered_below < float("inf")):
        raise ValueError(f"layered_below = {layered_below!r} must be finite and >= 0 (0: never)")
    if spacing not in ("uniform", "graded"):
        raise ValueError(f'spacing = {spacing!r} must be "uniform" or "graded"')
    if acceptance is None:
        acceptance = 0.0  # the solver's default, as the command line's (1e-9; 1e-4 by the boundary-element method)
    return Result(_rhabel._solve_scene(_json_text(scene, "scene"), _os.getcwd(), grid, bool(displacement),
                                       float(tolerance), bool(residual), acceptance, threads, time_limit, layered_below,
                                       spacing == "graded", bool(profile_knots)))


def sweep(sweep, out=None, threads=0, progress=True, tolerance=1e-12, acceptance=None, time_limit=0,
          profile_knots=False):
    """Solve every scene of a sweep: the rows of ``rhabel sweep SWEEP.json``, by the same code.

    Parameters
    ----------
    sweep : dict, or a path to a sweep JSON file
        The sweep schema of ``rhabel sweep``: ``{"scene": {...} or "FILE.json",
        "axes": [{"path": "speed", "log_range": {"from": 1e-6, "to": 100, "count": 41}}, ...],
        "combine": "product" or "zip"}``. Relative files (the scene, a master curve, a profile)
        are relative to the sweep file, or to the working directory for a dict.
    out : path or None
        A file the rows are written to as they complete (CSV with a header; JSON lines when the
        name ends in ``.jsonl``), resumable as the command line's ``--out``: rows already in the
        file are kept and only the missing ones solved; at the end it holds every row once, in
        row order. A file whose rows were solved with another tolerance, acceptance or
        profile_knots is refused (ValueError naming both), never mixed. None (default): no file.
    threads : int >= 0
        Rows solved at the same time (default 0: every core).
    progress : bool
        Show progress (tqdm when installed, else a line on stderr).
    tolerance, acceptance, time_limit, profile_knots
        Each row's solve options, as for solve() (and ``rhabel sweep --tolerance/--acceptance/
        --time-limit/--profile-knots``).

    Returns
    -------
    list of Record
        One per row, in row order, with the columns of the command line's CSV as keys (``row``,
        the swept paths, the solve options ``tolerance``, ``acceptance`` (None: the solver's
        default) and, for a sampled profile, ``profile_knots``, then ``status``, ``alpha``,
        ``E1``, ..., ``seconds``, ``message``); numbers
        equal to the command line's bit for bit (but ``seconds``), empty fields None. A scene
        that fails is a row too (its ``status`` and ``message``).

    Ctrl-C stops the rows under way (KeyboardInterrupt); the rows done stay in ``out``.
    """
    import os
    if isinstance(sweep, (str, os.PathLike)):
        path = os.fspath(sweep)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        source, directory = path, os.path.dirname(os.path.abspath(path))
    elif isinstance(sweep, dict):
        text = _json_text(sweep, "sweep")
        source, directory = "sweep", os.getcwd()
    else:
        raise ValueError(f"sweep must be a dict or the path of a sweep file, got {type(sweep).__name__}")
    if isinstance(threads, bool) or not isinstance(threads, int) or not 0 <= threads <= 1024:
        raise ValueError(f"threads = {threads!r} must be an integer in [0, 1024] (0: every core)")
    tolerance = float(tolerance)
    if not 1e-15 <= tolerance <= 1e-2:
        raise ValueError(f"tolerance = {tolerance!r} is outside the valid range [1e-15, 0.01]")
    acceptance = 0.0 if acceptance is None else float(acceptance)
    if acceptance != 0.0 and not 1e-15 <= acceptance <= 0.1:
        raise ValueError(f"acceptance = {acceptance!r} is outside the valid range [1e-15, 0.1]")
    time_limit = float(time_limit)
    if not (time_limit >= 0 and time_limit < float("inf")):
        raise ValueError(f"time_limit = {time_limit!r} must be finite and >= 0 (0: no limit)")
    handle = _rhabel._Sweep(text, source, directory)
    out = "" if out is None else os.fspath(out)
    jsonl = not out or out.endswith(".jsonl")
    bar = _progress(handle.rows) if progress else None
    try:
        lines = handle.run(out, jsonl, threads, tolerance, acceptance, time_limit, bool(profile_knots),
                           bar.update if bar else None)
    finally:
        if bar:
            bar.close()
    columns = handle.columns()
    return [_sweep_row(line, columns, jsonl) for line in lines]


def fit_material(curve, speed, length, temperature=None, wlf=None, window_decades=0.5, threshold=0.05):
    """The local power law E(t) = E1 t^-alpha of a measured master curve at omega0 = speed/length:
    ``rhabel fit-material CURVE --speed U --length L [--temperature T --wlf C1,C2,T_ref] --json``,
    by the same code.

    Parameters
    ----------
    curve : path
        The master curve, a CSV with the columns omega,E_storage,E_loss or f_hz,E_storage,E_loss or
        omega,E_abs,tan_delta.
    speed, length : float > 0
        The sliding speed U and the contact length L: omega0 = U/L.
    temperature : float or None, wlf : {"C1", "C2", "T_ref"} or (C1, C2, T_ref) or None
        Together: the curve shifted to that temperature by the WLF equation first.
    window_decades : float in [0.01, 5]
        Half width of the fit window in decades (default 0.5).
    threshold : float in [1e-6, 1]
        The status is "poor_power_law" when the two alpha estimates differ by more (default 0.05).

    Returns
    -------
    Record
        alpha, E1, omega0, alpha_slope, alpha_tan_delta, modulus, window, status ("ok",
        "poor_power_law", "window_clipped"), warning, master_curve, points (and temperature,
        log10_aT when shifted): the command line's JSON, bit for bit.
    """
    import os

    def number(value, name, lo, hi, lo_open):
        """value as a float in (lo, hi] (lo_open) or [lo, hi], as the command line's option checks."""
        try:
            if isinstance(value, (bool, str)):
                raise TypeError
            value = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name} = {value!r} is not a number") from None
        if not ((value > lo if lo_open else value >= lo) and value <= hi):
            raise ValueError(f"{name} = {value!r} is not in {'(' if lo_open else '['}{lo:g}, {hi:g}]")
        return value

    big = 1.7976931348623157e308
    speed = number(speed, "speed", 0.0, big, True)
    length = number(length, "length", 0.0, big, True)
    window_decades = number(window_decades, "window_decades", 0.01, 5.0, False)
    threshold = number(threshold, "threshold", 1e-6, 1.0, False)
    if (temperature is None) != (wlf is None):
        raise ValueError("temperature and wlf go together (the WLF shift to that temperature)")
    constants = None
    if wlf is not None:
        if isinstance(wlf, dict):
            if any(k not in wlf for k in ("C1", "C2", "T_ref")) or len(wlf) != 3:
                raise ValueError(f"wlf must have the keys C1, C2, T_ref, got {list(wlf)}")
            wlf = (wlf["C1"], wlf["C2"], wlf["T_ref"])
        try:
            wlf = tuple(wlf)
        except TypeError:
            raise ValueError(f"wlf = {wlf!r} must be (C1, C2, T_ref) or a dict of them") from None
        if len(wlf) != 3:
            raise ValueError(f"wlf needs three numbers C1, C2, T_ref, got {len(wlf)}")
        constants = [number(c, f"wlf.{key}", -big, big, False) for c, key in zip(wlf, ("C1", "C2", "T_ref"))]
        temperature = number(temperature, "temperature", -big, big, False)
    return Record(_rhabel._fit_material(os.fspath(curve), speed, length, temperature, constants, window_decades,
                                        threshold))


class _progress:
    """Progress of a sweep: tqdm when installed, else one line on stderr rewritten in place."""

    def __init__(self, total):
        self.total, self.done = total, 0
        try:
            from tqdm import tqdm
            self.bar = tqdm(total=total, unit="row")
        except ImportError:
            self.bar = None

    def update(self, done, todo):
        step = done - self.done
        self.done = done
        if self.bar is not None:
            self.bar.update(step)
        else:
            import sys
            print(f"\rrhabel.sweep: {done}/{todo} rows", end="", file=sys.stderr, flush=True)

    def close(self):
        if self.bar is not None:
            self.bar.close()
        elif self.done:
            import sys
            print(file=sys.stderr)


def _sweep_row(line, columns, jsonl):
    """A row's line (CSV or a JSON line) as a Record keyed by the columns."""
    if jsonl:
        return Record(_json.loads(line))
    import csv
    fields = next(csv.reader([line.rstrip("\n")]))
    row = Record()
    for name, text in zip(columns, fields):
        if name in ("status", "message"):
            row[name] = text
        elif not text:
            row[name] = None
        else:
            try:
                row[name] = _json.loads(text)
            except ValueError:  # a swept string value
                row[name] = text
    return row


def trial_interval(scene, a, b, tolerance=1e-12):
    """The trial field of the paper's Section 4 on a PRESCRIBED contact interval [a, b].

    For the scene's single indentor, the unique solution of the Abel equation (8) on [a, b] for
    the indentor's own profile that is bounded at the leading edge a and unbounded at the trailing
    edge b (index nu = 0: p ~ (t - a)^gam (b - t)^del with gam = (1 - 2 alpha - beta)/2,
    del = (beta - 1)/2), with nothing scaled: its load is whatever (8) gives. Returns that field's
    load and its hysteretic friction C_f = int f' p / int p. At the true contact interval of a
    smooth indentor (rhabel.solve) the trial field is the true one (its trailing-edge intensity
    vanishes), so the load and C_f are the solution's.

    Section 4 of the paper conjectures that among the trial intervals carrying a given load, C_f
    is stationary at the true one (the notebook two_indentors of the source distribution measures
    it for the parabola and the wedge).

    Parameters
    ----------
    scene : dict
        A scene as for rhabel.solve with exactly one indentor, "parabolic" or "wedge" (a flat
        punch's interval is fixed by its face: ValueError). The indentor's ``load`` is validated
        but not used. The wedge's apex singularity is built in as in rhabel.solve when the apex
        lies inside (a, b).
    a, b : float
        Leading and trailing edge, absolute abscissae (the apex is the indentor's ``apex``),
        finite, a < b.
    tolerance : float in (0, 1)
        Relative tolerance of the density's expansion (default 1e-12).

    Returns
    -------
    Record
        ``load`` (int p over [a, b], N/m), ``hysteretic_friction`` (C_f of the trial field) and
        ``error_estimate`` (estimated relative error of the density: an estimate, not a bound).

    Raises ValueError for an invalid scene, more than one indentor, a flat punch, a >= b, a
    non-finite edge, or an interval whose load or C_f is beyond the double range. Releases the GIL.

    Example
    -------
    >>> sc = {"material": {"alpha": 0.3, "E1": 1.0, "nu": 0.5, "coulomb": 0}, "speed": 1.0,
    ...       "indentors": [{"shape": "parabolic", "radius": 1.0, "load": 1.0}]}
    >>> t = rhabel.trial_interval(sc, -0.6, 0.5)
    >>> t.load, t.hysteretic_friction
    """
    text = _json_text(scene, "scene")
    spec = _rhabel._validate_scene(text, _os.getcwd())
    if "indentors" not in spec or len(spec["indentors"]) != 1:
        count = len(spec["indentors"]) if "indentors" in spec else "no"
        raise ValueError(f"trial_interval: the scene has {count} indentors; a trial interval belongs to exactly one")
    if not (0 < tolerance < 1):
        raise ValueError(f"trial_interval: tolerance = {tolerance!r} is outside the valid range (0, 1)")
    a, b = _finite(a, "a"), _finite(b, "b")
    if not _math.isfinite(b - a):
        raise ValueError(f"trial_interval: b - a = {b!r} - {a!r} overflows a double: the interval must be shorter")
    try:
        result = _rhabel._trial_interval(text, _os.getcwd(), a, b, float(tolerance))
    except OverflowError as e:
        raise ValueError(f"trial_interval: the interval [a, b] = [{a!r}, {b!r}] takes the field beyond the double "
                         f"range ({e})") from None
    if not all(_math.isfinite(result[k]) for k in ("load", "hysteretic_friction")):
        raise ValueError(f"trial_interval: the interval [a, b] = [{a!r}, {b!r}] gives a load or C_f beyond the double "
                         f"range (load {result['load']!r}, C_f {result['hysteretic_friction']!r}): choose an interval "
                         "of a length closer to the indentor's scale")
    return result


def _finite(value, name):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"trial_interval: {name} = {value!r} must be a finite number") from None
    if not _math.isfinite(x):
        raise ValueError(f"trial_interval: {name} = {x!r} must be a finite number")
    return x


def _grid(grid):
    if isinstance(grid, bool) or not hasattr(grid, "__index__"):
        raise ValueError(f"grid = {grid!r} must be an integer: 0 (no samples) or in [2, 1000000]")
    grid = grid.__index__()
    if not (grid == 0 or 2 <= grid <= 1_000_000):
        raise ValueError(f"grid = {grid} is outside the valid range: 0 (no samples) or [2, 1000000]")
    return grid


def validate_scene(scene):
    """The scene as rhabel.solve validates it (a new dict, numbers as floats, ``apex`` filled
    in, a profile's file read into its samples ``x`` and ``z``): the command line's parser and
    checks. Raises ValueError naming the first offending field."""
    return _rhabel._validate_scene(_json_text(scene, "scene"), _os.getcwd())


def load_scene(path):
    """Read a scene JSON file (a path or an open text file) into a dict. Duplicate keys are
    rejected (ValueError), as by the command line; validation happens in solve()."""
    def pairs(items):
        out = {}
        for key, value in items:
            if key in out:
                raise ValueError(f"{key} appears twice in the same object "
                                 "(duplicate keys are rejected: which one was meant?)")
            out[key] = value
        return out

    if hasattr(path, "read"):
        return _json.load(path, object_pairs_hook=pairs)
    with open(path, encoding="utf-8") as f:
        scene = _json.load(f, object_pairs_hook=pairs)
    # A profile's CSV and a master curve are relative to the scene file, as for the command line.
    import os
    for key, field in (("profile", "file"), ("material", "master_curve")):
        item = scene.get(key) if isinstance(scene, dict) else None
        if isinstance(item, dict) and isinstance(item.get(field), str) and not os.path.isabs(item[field]):
            item[field] = os.path.join(os.path.dirname(os.fspath(path)), item[field])
    return scene


GaussJacobiRule = _namedtuple("GaussJacobiRule", ["x", "hi_minus_x", "x_minus_lo", "weight"])
GaussJacobiRule.__doc__ = """Gauss-Jacobi rule on [lo, hi]: nodes x (increasing), their distances
to both ends hi - x and x - lo (on [-1, 1]: 1 - x and 1 + x), computed without cancellation, and
positive weights. A tuple: ``x, hi_minus_x, x_minus_lo, w = rhabel.gauss_jacobi(...)``."""


def gauss_jacobi(n, p, q, lo=-1.0, hi=1.0):
    """The n-point Gauss-Jacobi rule for the weight (hi - t)^p (t - lo)^q on [lo, hi]
    (p belongs to the right end, q to the left one; on [-1, 1]: (1 - x)^p (1 + x)^q):

        sum_i w_i f(x_i) = int_lo^hi (hi - t)^p (t - lo)^q f(t) dt

    exactly for every polynomial f of degree <= 2n - 1. n >= 1, p, q > -1.

    Returns a GaussJacobiRule (a named tuple of four NumPy arrays built from the C++ vectors
    without a per-element copy): ``x``, ``hi_minus_x``, ``x_minus_lo`` (on [-1, 1]: 1 - x and
    1 + x, accurate even where x itself keeps only a few digits of them: use them for endpoint
    factors such as (1 - x)^p) and ``weight``.

    Accuracy (measured against tables computed to 60 digits): for
    p, q in (-1, 5] and n <= 10^6 every weight and min(1 - x, 1 + x) to <= 45 eps relative
    (worst measured 8.9 and 3.2 eps). O(n): n = 10^4 in ~0.6 ms, 10^6 in ~60-90 ms.
    Raises ValueError for n = 0 or above 10^6 (checked before allocating), p or q outside (-1, 30],
    lo >= hi. Releases the GIL.

    Example: ``x, _, _, w = rhabel.gauss_jacobi(10, 0.25, -0.5)``; ``w @ x**3``.
    """
    return GaussJacobiRule(*_rhabel.gauss_jacobi(n, p, q, lo, hi))


def jacobi_p(n, p, q, x):
    """Jacobi polynomial P_n^(p,q)(x) (orthogonal on [-1, 1] for the weight (1 - x)^p (1 + x)^q),
    elementwise over x (a float or any array-like; a float in, a float out). p, q > -1, x finite.

    Three-term recurrence, in Reinsch's difference form near the ends and the endpoint
    hypergeometric series in the boundary layers n^2 (1 -+ x) <= 2: relative error O(n eps)
    away from the zeros (measured <= 0.3 (n + 10) eps relative to the local scale for n <= 10^6).
    Raises ValueError for p or q <= -1 or a non-finite
    x, OverflowError when the value exceeds the double range (|x| far beyond 1). Releases the GIL.
    """
    return _rhabel.jacobi_p(n, p, q, x)
