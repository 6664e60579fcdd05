"""Reading a gjklab results archive (HDF5, schema in results/README.md) into pandas.

The archive is columnar already: every group of 1-D datasets becomes one DataFrame, row i
being case i in every frame. HDF5 enum columns (shape kinds, terminations, failure classes,
answer methods) become pandas categoricals with the enum's names, in the enum's order.
"""

from dataclasses import dataclass, field

import h5py
import numpy as np
import pandas as pd


@dataclass
class Archive:
    """One run: its cases, the exact answers and one frame per algorithm."""

    cases: pd.DataFrame
    exact: "pd.DataFrame | None"  # None when the run had no oracle
    algorithms: dict = field(default_factory=dict)  # group name -> DataFrame
    attrs: dict = field(default_factory=dict)  # root attributes: provenance, experiment, ...
    complete: bool = False
    # Nonconvex families only (/meshes): how each case's truth was decided, and per algorithm
    # group the pieces and piece pairs its queries ran on.
    mesh_exact: "pd.DataFrame | None" = None
    mesh_algorithms: dict = field(default_factory=dict)  # group name -> DataFrame


def _text(value):
    return value.decode() if isinstance(value, bytes) else value


def _column(dataset, rows):
    """A dataset's first `rows` rows as one or more named columns."""
    data = dataset[:rows]
    mapping = h5py.check_enum_dtype(dataset.dtype)
    if mapping is not None:
        names = sorted(mapping, key=mapping.get)
        codes = {value: i for i, value in enumerate(mapping[n] for n in names)}
        return {dataset.name.rsplit("/", 1)[-1]: pd.Categorical.from_codes(
            [codes[v] for v in data.tolist()], categories=names)}
    name = dataset.name.rsplit("/", 1)[-1]
    if data.ndim == 2:
        # Points (rows x 3): one column per coordinate, so the frame stays flat.
        return {f"{name}_{axis}": data[:, k] for k, axis in enumerate("xyz"[: data.shape[1]])}
    if data.dtype.kind in "SO":
        return {name: [_text(v) for v in data.tolist()]}
    return {name: data}


def _frame(group, rows):
    columns = {}
    for name, dataset in group.items():
        if isinstance(dataset, h5py.Dataset) and dataset.ndim in (1, 2):
            columns.update(_column(dataset, rows))
    return pd.DataFrame(columns)


def read_archive(path):
    """Reads an archive written by gjklab run (or gjklab.run) into an Archive of DataFrames.

    An incomplete archive (an interrupted run, FILE.h5.tmp) is read up to its last
    checkpoint, as gjklab's own reader does; Archive.complete says which it was."""
    with h5py.File(path, "r") as f:
        attrs = {k: _text(v) for k, v in f.attrs.items()}
        complete = int(attrs.get("complete", 0)) == 1
        rows = len(f["cases/case_id"])
        if not complete and "checkpoint_cases" in attrs:
            rows = min(rows, int(attrs["checkpoint_cases"]))
        cases = _frame(f["cases"], rows)
        family_names = [_text(n) for n in np.atleast_1d(f.attrs.get("family_names", []))]
        if family_names and "family" in cases:
            cases["family"] = pd.Categorical.from_codes(cases["family"].astype(int),
                                                        categories=family_names)
        exact = _frame(f["exact"], rows) if "exact" in f else None
        algorithms = {name: _frame(group, rows) for name, group in f["algorithms"].items()}
        mesh_exact = _frame(f["meshes/exact"], rows) if "meshes/exact" in f else None
        mesh_algorithms = ({name: _frame(group, rows)
                            for name, group in f["meshes/algorithms"].items()}
                           if "meshes/algorithms" in f else {})
    return Archive(cases=cases, exact=exact, algorithms=algorithms, attrs=attrs,
                   complete=complete, mesh_exact=mesh_exact, mesh_algorithms=mesh_algorithms)
