#!/usr/bin/env python3
"""Checks that h5py reads a gjklab results archive with the dtypes of results/README.md.

Usage: archive_check.py ARCHIVE.h5     (exit status 0 when every check passes)
"""
import sys

import h5py
import numpy as np

SHAPES = {"sphere_points": 0, "ball_points": 1, "cube_points": 2, "gaussian": 3,
          "box": 4, "cone": 5, "cylinder": 6, "uv_sphere": 7, "flat_points": 8,
          "collinear_points": 9, "duplicate_points": 10, "single_point": 11, "sliver": 12,
          "prism": 13, "pyramid": 14, "from_file": 15, "mesh": 16, "sphere": 17,
          "capsule": 18, "segment": 19, "needle": 20, "rod": 21, "wedge": 22, "plate": 23}
PLACEMENTS = {"separated": 0, "overlapping": 1, "random": 2, "touching": 3, "as_given": 4}
CONTACTS = {"separated": 0, "touching_band": 1, "intersecting": 2}
METHODS = {"certified": 0, "qp": 1, "none": 2, "mesh_truth": 3}
TERMINATIONS = {"converged": 0, "step_limit": 1, "no_progress": 2, "degenerate_simplex": 3,
                "cycling": 4, "numerical_failure": 5, "invalid_input": 6}

CASES = {"case_id": np.uint64, "family": np.uint32, "shape_a": SHAPES, "shape_b": SHAPES,
         "placement": PLACEMENTS, "vertices_a": np.int32, "vertices_b": np.int32,
         "scale": np.float64, "size": np.float64, "intended_gap": np.float64,
         "radius_a": np.float64, "radius_b": np.float64}
EXACT = {"intersect": bool, "distance": np.float64, "distance2_num": str, "distance2_den": str,
         "depth": np.float64, "hull_vertices_a": np.int32, "hull_vertices_b": np.int32,
         "contact": CONTACTS, "method": METHODS, "depth_method": METHODS}
FAILURES = {"none": 0, "touching_band": 1, "step_limit": 2, "no_progress": 3,
            "degenerate_simplex": 4, "cycling": 5, "non_finite": 6, "wrong_boolean": 7,
            "distance_error": 8}
ALGORITHM = {"intersect": bool, "distance": np.float64, "abs_error": np.float64,
             "rel_error": np.float64, "boolean_correct": bool, "iterations": np.int32,
             "support_calls": np.int32, "termination": TERMINATIONS, "time_ns": np.float64,
             "failure": FAILURES, "depth": np.float64, "depth_abs_error": np.float64,
             "depth_rel_error": np.float64, "witness_error_a": np.float64,
             "witness_error_b": np.float64, "witness_distance_error": np.float64,
             "rounded_exact_distance": np.float64, "rounded_exact_depth": np.float64,
             "lower_bound": np.float64, "upper_bound": np.float64}
ALGORITHM_VEC3 = ("witness_a", "witness_b")
GEOMETRY = {"case_id": np.uint64, "a_offset": np.uint64, "a_count": np.uint64,
            "b_offset": np.uint64, "b_count": np.uint64}


def check_column(ds, kind, rows):
    name = ds.name
    assert ds.ndim == 1 and ds.shape[0] == rows, f"{name}: shape {ds.shape}, expected ({rows},)"
    assert ds.maxshape == (None,), f"{name}: not extendible"
    assert ds.chunks is not None and ds.compression == "gzip", f"{name}: not chunked + deflate"
    values = ds[()]
    if kind is bool:
        assert ds.dtype == np.bool_ and values.dtype == np.bool_, f"{name}: dtype {ds.dtype}"
    elif kind is str:
        info = h5py.check_string_dtype(ds.dtype)
        assert info is not None and info.length is None and info.encoding == "utf-8", name
        assert all(isinstance(s, str) for s in ds.asstr()[()]), f"{name}: does not decode"
    elif isinstance(kind, dict):
        assert h5py.check_enum_dtype(ds.dtype) == kind, f"{name}: enum {h5py.check_enum_dtype(ds.dtype)}"
        assert values.dtype == np.uint8, f"{name}: base {values.dtype}"
        assert set(values.tolist()) <= set(kind.values()), f"{name}: value outside the enum"
    else:
        assert ds.dtype == np.dtype(kind), f"{name}: dtype {ds.dtype}, expected {np.dtype(kind)}"
        if ds.dtype.itemsize > 1:
            assert ds.shuffle, f"{name}: no shuffle filter"


def check_group(group, columns, rows):
    missing = set(columns) - set(group.keys())
    assert not missing, f"{group.name}: missing {sorted(missing)}"
    for name, kind in columns.items():
        check_column(group[name], kind, rows)


def main(path):
    with h5py.File(path, "r") as f:
        a = f.attrs
        assert a["schema_version"] == 2 and a["schema_version"].dtype == np.int32
        for key in ("experiment_name", "experiment_text", "start_time", "end_time",
                    "gjklab_version", "git_commit", "compiler", "hdf5_version"):
            assert isinstance(a[key], str), f"attribute {key} is {type(a[key])}"
        assert a["seed"].dtype == np.uint64 and a["cases_planned"].dtype == np.uint64
        assert a["touching_band"].dtype == np.float64
        assert a["complete"] == 1 and a["complete"].dtype == np.uint8
        assert list(a.keys())[-1] == "complete", "complete is not the last attribute"
        oracle = bool(a["oracle"])
        families = [str(s) for s in a["family_names"]]
        algorithms = [str(s) for s in a["algorithm_names"]]
        assert all(isinstance(s, str) for s in a["algorithm_names"])

        rows = f["cases/case_id"].shape[0]
        check_group(f["cases"], CASES, rows)
        assert f["cases/family"][()].max(initial=0) < max(len(families), 1)
        assert ("exact" in f) == oracle, "/exact must exist exactly when the oracle is on"
        if oracle:
            check_group(f["exact"], EXACT, rows)
        assert list(f["algorithms"].keys()) == sorted(algorithms)
        for name in algorithms:
            g = f["algorithms"][name]
            check_group(g, ALGORITHM, rows)
            for column in ALGORITHM_VEC3:
                v = g[column]
                assert v.shape == (rows, 3) and v.dtype == np.float64, v.name
                assert v.maxshape == (None, 3) and v.compression == "gzip", v.name
            assert all(isinstance(v, str) for v in g.attrs.values()), f"{g.name}: options"

        geo = f["geometry"]
        kept = geo["case_id"].shape[0]
        check_group(geo, GEOMETRY, kept)
        for side in ("a", "b"):
            v = geo["vertices_" + side]
            assert v.ndim == 2 and v.shape[1] == 3 and v.dtype == np.float64, v.name
            assert v.maxshape == (None, 3) and v.compression == "gzip", v.name
            end = geo[side + "_offset"][()] + geo[side + "_count"][()]
            assert (end <= v.shape[0]).all(), f"{v.name}: offsets past the end"
        assert np.isin(geo["case_id"][()], f["cases/case_id"][()]).all()
    print(f"{path}: ok ({rows} cases, {len(algorithms)} algorithms, {kept} with geometry)")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
