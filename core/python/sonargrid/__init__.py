# SPDX-License-Identifier: BSD-3-Clause
"""SonarGrid's core for Python: read sonar logs, build occupancy grids with the classic sonar
models and update rules, score them against a reference or without one, and sweep parameters.

Every function runs the same core code as ``sonargrid-cli``; dictionaries use the CLI's JSON keys.
See docs/python.md in the SonarGrid sources.
"""

from ._core import (  # noqa: F401  (re-exported)
    Error,
    Log,
    LogError,
    Map,
    ParameterError,
    Reference,
    goodness,
    map,
    models,
    read_log,
    read_reference,
    score,
    set_threads,
    threads,
)
from . import _core

__all__ = [
    "Error", "Log", "LogError", "Map", "ParameterError", "Reference", "goodness", "map", "models",
    "read_log", "read_reference", "score", "set_threads", "sweep", "threads",
]


def _axis_text(name, values):
    if isinstance(values, str):
        return f"{name}={values}"
    # repr() of a float is the shortest text that reads back to the same double, as the CLI's
    # grammar reads it.
    return f"{name}=" + ",".join(repr(float(v)) for v in values)


def sweep(log, *, model, rule, grid, ties=(), metrics=("vsdns",), reference=None,
          second_log=None, cell=0.05, pose="odom", threads=None, as_frame=None, **params):
    """Maps ``log`` once per parameter set and measures each map (docs/sweeps.md).

    ``grid`` lists the axes, the first outermost: texts in the CLI's grammar
    (``"p2=0.05:0.05:0.2"``, ``"p5=6,7,8"``) or a dict ``{"p5": [6, 7, 8]}``. ``ties`` are texts
    such as ``"p1=1-p4"``. ``metrics`` are the CLI's ``--metric`` names. Further keywords set the
    base parameters. Rows are in set order: ``index``, every parameter, then the metrics' columns
    (None where undefined), the same numbers as ``sonargrid-cli sweep`` writes to its CSV at any
    thread count. Returns a list of dicts, or a pandas DataFrame when ``as_frame`` is true (by
    default: when pandas can be imported).
    """
    if isinstance(grid, dict):
        axes = [_axis_text(k, v) for k, v in grid.items()]
    elif isinstance(grid, str):
        axes = [grid]
    else:
        axes = list(grid)
    if isinstance(ties, str):
        ties = [ties]
    if isinstance(metrics, str):
        metrics = [metrics]
    rows = _core._sweep_rows(log, model=model, rule=rule, grid=axes, ties=list(ties),
                             metrics=list(metrics), reference=reference, second_log=second_log,
                             cell=cell, pose=pose, threads=threads, **params)
    if as_frame is None:
        try:
            import pandas  # noqa: F401
        except ImportError:
            as_frame = False
        else:
            as_frame = True
    if as_frame:
        import pandas
        return pandas.DataFrame(rows)
    return rows
