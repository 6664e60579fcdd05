"""gjklab: GJK collision and distance algorithms, their peers and an exact oracle.

The compiled part (gjklab._gjklab) calls the same C++ API as the ``gjklab`` command line:

    query(a, b, algorithm="gjk-johnson", **options)  one algorithm on two n x 3 float64 arrays
    Shape(points)                                     a shape built once, for many queries
    exact(a, b, depth=False)                          the exact answer, as fractions.Fraction
    algorithms()                                      every algorithm, its options and defaults
    families()                                        every shape an experiment's family can name
    real_objects()                                    names for shape = "real_object"
    real_object_folder()                              the folder of their mesh files
    read_points(path)                                 a point or mesh file as an n x 3 array
    read_closed_mesh(path)                            a closed triangle mesh: (vertices, faces)
    exact_mesh(a, b)                                  the exact answer for two closed meshes' solids
    decompose(mesh, method="exact")                   a closed mesh's convex pieces, by name
    query_mesh(a, b, algorithm, decomposition)        an algorithm on two closed meshes
    prism_mesh(polygon, z0, z1), lathe_mesh(profile, segments, ring)
                                                      generated closed meshes
    run(experiment, out=..., threads=...)             an experiment file (or TOML text) -> archive

and read_archive(path) reads an archive into pandas DataFrames.
"""

from ._gjklab import (
    ExactAnswer,
    Result,
    RunReport,
    Shape,
    algorithms,
    decompose,
    exact,
    exact_mesh,
    families,
    lathe_mesh,
    prism_mesh,
    query,
    query_mesh,
    read_closed_mesh,
    read_points,
    real_object_folder,
    real_objects,
    run,
)
from .archive import Archive, read_archive

__all__ = [
    "Archive",
    "ExactAnswer",
    "Result",
    "RunReport",
    "Shape",
    "algorithms",
    "decompose",
    "exact",
    "exact_mesh",
    "families",
    "lathe_mesh",
    "prism_mesh",
    "query",
    "query_mesh",
    "read_archive",
    "read_closed_mesh",
    "read_points",
    "real_object_folder",
    "real_objects",
    "run",
]
