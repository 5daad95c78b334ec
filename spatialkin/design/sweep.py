"""Sweeps: evaluate thousands of looper geometries (a full crank turn each) on local processes or a Dask
cluster; a geometry that fails is a row with the reason, never a lost run. A local worker process that dies
breaks the whole pool: that raises (from a script, the usual cause is a main module without
``if __name__ == "__main__":``, which the workers re-import).

    from spatialkin.design import LooperDesign, sweep, grid_space
    space = grid_space(crank_radius=np.linspace(6, 10, 20), rocker_length=np.linspace(25, 35, 20))
    table = sweep(space, ("swing", "min_transmission"), base=LooperDesign.reference())
    table = sweep(space, ("swing",), client=distributed.Client(...))        # on a Dask cluster
"""
import concurrent.futures
import itertools
import math
import os
from concurrent.futures.process import BrokenProcessPool

import numpy as np

from ..tracing.batch import worker_context
from .._lib.validation import check_count
from .looper import LooperDesign
from .params import PARAMETERS, check_names

#: Scalar outputs a sweep can compute per geometry (angles in rad, lengths in the drive's unit, time in 1/omega).
OUTPUTS = {
    "swing": "max u2 - min u2 over the turn (turning points refined by Newton)",
    "u2_min": "smallest rocker angle u2", "u2_max": "largest rocker angle u2",
    "v2_min": "smallest rocker angle v2", "v2_max": "largest rocker angle v2",
    "u2_max_at": "crank angle of the u2 maximum", "u2_min_at": "crank angle of the u2 minimum",
    "min_transmission": "smallest transmission angle (sampled)",
    "min_transmission_at": "crank angle of the smallest transmission angle",
    "assembly_margin": "smallest assembly margin over the turn (> 0: assembles everywhere)",
    "tip_path_length": "length of the looper tip's path over the turn (polyline of the samples)",
    "tip_speed_max": "largest looper-tip speed", "tip_acceleration_max": "largest looper-tip acceleration",
    "ball_speed_max": "largest ball-centre speed", "ball_acceleration_max": "largest ball-centre acceleration",
}
#: Crank angles sampled per geometry by default (1 deg steps, both ends).
SWEEP_SAMPLES = 361
#: Geometries per task sent to a worker (amortises the task overhead).
CHUNK = 16
#: Width of the 'reason' column (characters).
REASON_WIDTH = 160
#: Why a local pool breaks, and what to do (the RuntimeError sweep raises then).
BROKEN_POOL = ("a worker process of spatialkin.design.sweep died ({rows} geometries on {workers} processes), so no "
               "geometry can be evaluated there. From a script the usual cause is a main module without "
               "'if __name__ == \"__main__\":' around its code: the worker processes re-import it, and Python refuses "
               "to start them from that import; put the script's calls under the guard, or pass processes=0 to run "
               "in this process (client= to run on a Dask cluster)")


def grid_space(**axes):
    """The Cartesian product of parameter axes: {name: (M,)} with M = product of the axes' lengths.

    Parameters
    ----------
    **axes
        name=values (K,) for design parameters (spatialkin.design.params.PARAMETERS).

    Returns
    -------
    dict
        {name: ndarray (M,)}, the last axis varying fastest.

    Raises
    ------
    ValueError
        With no axis, or naming an unknown parameter.

    Examples
    --------
    >>> from spatialkin.design import grid_space
    >>> space = grid_space(crank_radius=[7.0, 8.0], rocker_length=[29.0, 30.0, 31.0])
    >>> space["crank_radius"].tolist(), space["rocker_length"].tolist()
    ([7.0, 7.0, 7.0, 8.0, 8.0, 8.0], [29.0, 30.0, 31.0, 29.0, 30.0, 31.0])
    """
    if not axes:
        raise ValueError("grid_space needs at least one axis name=values")
    check_names(tuple(axes), "axes")
    values = [np.atleast_1d(np.asarray(v, dtype=float)) for v in axes.values()]
    rows = np.array(list(itertools.product(*values)), dtype=float).reshape(-1, len(values))
    return {name: rows[:, k] for k, name in enumerate(axes)}


def random_space(design, n, names=None, seed=0):
    """n geometries drawn uniformly within the design's bounds: {name: (n,)} for names (default design.free)."""
    names = design.free if names is None else check_names(names, "names")
    check_count("n", n)
    rng = np.random.default_rng(seed)
    return {name: rng.uniform(*design.bounds[name], size=n) for name in names}


def check_space(space):
    """(names, values (M, K)) of a space {name: (M,)}; ValueError naming 'space'."""
    if not isinstance(space, dict) or not space:
        raise ValueError("space must be a non-empty dict {parameter: values (M,)}")
    names = tuple(space)
    unknown = [n for n in names if n not in PARAMETERS]
    if unknown:
        raise ValueError(f"space: unknown design parameters {unknown}; known {list(PARAMETERS)}")
    cols = [np.atleast_1d(np.asarray(space[n], dtype=float)) for n in names]
    if any(c.ndim != 1 or len(c) != len(cols[0]) for c in cols):
        raise ValueError("space: every parameter needs a 1-D array of the same length")
    return names, np.column_stack(cols)


def evaluate(design, outputs, samples=SWEEP_SAMPLES):
    """The scalar outputs {name: float} of one geometry (one drive.solve over the turn)."""
    from .sensitivity import sensitivities
    angles = np.linspace(0.0, 2 * np.pi, samples)
    turning = any(o in ("swing", "u2_max_at", "u2_min_at", "assembly_margin") for o in outputs)
    s = sensitivities(design, angles, free=(), turning=turning)
    u2, v2 = s.rocker_angles.T
    out = {}
    for name in outputs:
        if name == "swing":
            out[name] = s.swing
        elif name in ("u2_min", "u2_max", "v2_min", "v2_max"):
            arr = u2 if name.startswith("u2") else v2
            if name.startswith("u2") and len(s.turning_u2):
                arr = np.concatenate([arr, s.turning_u2])
            out[name] = float(arr.min() if name.endswith("min") else arr.max())
        elif name in ("u2_max_at", "u2_min_at"):
            if len(s.turning_u2) < 2:
                out[name] = math.nan
            else:
                k = np.argmax(s.turning_u2) if name == "u2_max_at" else np.argmin(s.turning_u2)
                out[name] = float(np.mod(s.turning_points[k], 2 * np.pi))
        elif name == "min_transmission":
            out[name] = s.min_transmission
        elif name == "min_transmission_at":
            out[name] = float(angles[np.argmin(s.transmission_angle)])
        elif name == "assembly_margin":
            out[name] = s.assembly_margin
        elif name == "tip_path_length":
            out[name] = float(np.sum(np.linalg.norm(np.diff(s.tip, axis=0), axis=1)))
        else:
            arr = {"tip_speed_max": s.tip_velocity, "tip_acceleration_max": s.tip_acceleration,
                   "ball_speed_max": s.ball_velocity, "ball_acceleration_max": s.ball_acceleration}[name]
            out[name] = float(np.max(np.linalg.norm(arr, axis=1)))
    return out


def evaluate_chunk(base, names, rows, outputs, samples):
    """Worker task: rows (m, K) of parameter values on top of base (a dict from _portable) ->
    list of (ok, reason, output values)."""
    from ..geometry.frame import Frame
    results = []
    for row in rows:
        try:
            values = dict(base["values"], **dict(zip(names, map(float, row))))
            design = LooperDesign(values, crank_frame=Frame(*base["crank_frame"]), looper_link=base["looper_link"],
                                  branch=base["branch"])
            out = evaluate(design, outputs, samples)
            results.append((True, "", [out[o] for o in outputs]))
        except Exception as err:       # a failed geometry is a row with its reason
            results.append((False, f"{type(err).__name__}: {err}"[:REASON_WIDTH], [math.nan] * len(outputs)))
    return results


def _result(future, rows, width):
    """A finished task's rows; when the task itself failed (a cluster error, a Dask worker lost), its geometries
    become failed rows with the reason, so the rest of the run is kept. A broken local pool (BrokenProcessPool:
    none of its tasks can run) propagates, for sweep to raise."""
    try:
        return future.result()
    except BrokenProcessPool:
        raise
    except Exception as err:
        reason = f"worker failed: {type(err).__name__}: {err}"[:REASON_WIDTH]
        return [(False, reason, [math.nan] * width)] * rows


def _portable(design):
    return {"values": dict(design.values), "looper_link": design.looper_link, "branch": design.branch,
            "crank_frame": (design.crank_frame.origin.tolist(), design.crank_frame.rotation.tolist())}


def _context():
    """Worker processes forked from a server that has imported spatialkin once (its jitted kernels loaded, the
    reference geometry evaluated: design._warm), so a pool starts in milliseconds instead of a fresh interpreter
    per worker (spatialkin.tracing.batch.worker_context)."""
    return worker_context([__package__ + "._warm"])


def _progress(total, enabled):
    if enabled:
        try:
            from tqdm.auto import tqdm
            return tqdm(total=total, unit="geometry", desc="sweep")
        except ImportError:
            pass
    return None


def sweep(space, outputs=("swing", "min_transmission", "assembly_margin"), client=None, base=None,
          processes=None, samples=SWEEP_SAMPLES, chunk=CHUNK, progress=True, as_frame=None):
    """Evaluate every geometry of a design space over a full crank turn.

    Parameters
    ----------
    space : dict
        {parameter name: values (M,)}: row m is one geometry, the other parameters taken from base
        (see grid_space, random_space).
    outputs : sequence of str
        Names from OUTPUTS (scalars per geometry).
    client : dask.distributed.Client, optional
        Run the tasks on this Dask cluster; default: local processes (concurrent.futures).
    base : LooperDesign, optional
        The geometry the space varies (default LooperDesign.reference()).
    processes : int, optional
        Local worker processes (default os.cpu_count()); 0 runs in this process.
    samples : int
        Crank angles per geometry (a full turn, both ends).
    chunk : int
        Geometries per task.
    progress : bool
        Show a progress bar (if tqdm is installed).
    as_frame : bool, optional
        True: a pandas DataFrame (ValueError without pandas); False: a numpy structured array; None (default):
        a DataFrame when pandas is installed, else the structured array.

    Returns
    -------
    numpy structured array or pandas.DataFrame (M rows)
        The swept parameters, the outputs (angles in rad, lengths in the drive's unit, time in 1/omega with
        omega = 1), 'ok' (bool) and 'reason' (str, empty when ok). A geometry that fails (cannot be assembled,
        raises in its worker, its task lost on a Dask cluster) is a row with ok False, NaN outputs and the
        reason: a sweep never loses its run to one geometry.

    Raises
    ------
    ValueError
        Naming the argument: a space that is not a non-empty dict of 1-D arrays of one length over known
        parameters, unknown or repeated outputs, samples < 3, chunk < 1, processes < 0, a base that is not a
        LooperDesign, as_frame=True without pandas.
    RuntimeError
        A local worker process died, which breaks the pool (BrokenProcessPool, chained as the cause). From a
        script the usual cause is a main module without ``if __name__ == "__main__":`` (the workers re-import
        it); the message says so. processes=0 runs in this process.

    Notes
    -----
    Local workers are started by forkserver (spawn where the platform has no fork) and re-import the caller's
    main module: a script calls sweep under ``if __name__ == "__main__":``.

    See Also
    --------
    grid_space, random_space : design spaces.
    LooperDesign.sensitivities : the outputs of one geometry, with their derivatives.

    Examples
    --------
    Three crank radii of the reference drive, in this process (processes=0):

    >>> import numpy as np
    >>> from spatialkin.design import grid_space, sweep
    >>> space = grid_space(crank_radius=[7.0, 8.0, 9.0])
    >>> table = sweep(space, ("swing",), processes=0, progress=False, as_frame=False)
    >>> table.dtype.names
    ('crank_radius', 'swing', 'ok', 'reason')
    >>> table["ok"].tolist(), np.round(table["swing"], 3).tolist()
    ([True, True, True], [0.685, 0.649, 0.61])
    >>> sweep(space, ("speed",))
    Traceback (most recent call last):
    ...
    ValueError: outputs: unknown ['speed']; known [...]
    """
    names, rows = check_space(space)
    outputs = tuple([outputs] if isinstance(outputs, str) else outputs)
    bad = [o for o in outputs if o not in OUTPUTS]
    if bad or not outputs:
        raise ValueError(f"outputs: unknown {bad}; known {sorted(OUTPUTS)}")
    twice = sorted({o for o in outputs if outputs.count(o) > 1} | (set(outputs) & set(names)))
    if twice:
        raise ValueError(f"outputs: {twice} given twice (or also swept): each column of the table is named once")
    check_count("samples", samples, 3)
    check_count("chunk", chunk)
    base = LooperDesign.reference() if base is None else base
    if not isinstance(base, LooperDesign):
        raise ValueError(f"base must be a LooperDesign, got {type(base).__name__}")
    portable = _portable(base)
    chunks = [rows[i:i + chunk] for i in range(0, len(rows), chunk)]
    args = (portable, names)
    done = [None] * len(chunks)
    bar = _progress(len(rows), progress)
    try:
        if client is not None:
            from distributed import as_completed
            futures = client.map(evaluate_chunk, [args[0]] * len(chunks), [names] * len(chunks), chunks,
                                 [outputs] * len(chunks), [samples] * len(chunks), pure=False)
            index = {f.key: k for k, f in enumerate(futures)}
            for future in as_completed(futures):
                k = index[future.key]
                done[k] = _result(future, len(chunks[k]), len(outputs))
                if bar is not None:
                    bar.update(len(chunks[k]))
        elif processes == 0:
            for k, c in enumerate(chunks):
                done[k] = evaluate_chunk(portable, names, c, outputs, samples)
                if bar is not None:
                    bar.update(len(c))
        else:
            if processes is not None:
                check_count("processes", processes, 0)
            workers = processes or os.cpu_count() or 1
            try:
                with concurrent.futures.ProcessPoolExecutor(workers, mp_context=_context()) as pool:
                    futures = {pool.submit(evaluate_chunk, portable, names, c, outputs, samples): k
                               for k, c in enumerate(chunks)}
                    for future in concurrent.futures.as_completed(futures):
                        k = futures[future]
                        done[k] = _result(future, len(chunks[k]), len(outputs))
                        if bar is not None:
                            bar.update(len(chunks[k]))
            except BrokenProcessPool as err:
                raise RuntimeError(BROKEN_POOL.format(rows=len(rows), workers=workers)) from err
    finally:
        if bar is not None:
            bar.close()
    results = [r for part in done for r in part]
    dtype = [(n, "f8") for n in names] + [(o, "f8") for o in outputs] + [("ok", "?"), ("reason", f"U{REASON_WIDTH}")]
    table = np.zeros(len(rows), dtype=dtype)
    for k, n in enumerate(names):
        table[n] = rows[:, k]
    for m, (ok, reason, values) in enumerate(results):
        table["ok"][m], table["reason"][m] = ok, reason
        for o, v in zip(outputs, values):
            table[o][m] = v
    if as_frame is False:
        return table
    try:
        import pandas
    except ImportError:
        if as_frame:
            raise ValueError("as_frame=True needs pandas (pip install pandas)") from None
        return table
    return pandas.DataFrame.from_records(table)
