#!/usr/bin/python3
"""tools/plot on every committed reference archive, and the gallery results/figures/README.md.

Usage: tests/plot_check.py [SOURCE_DIR]   (default: the folder above tests/)

Checks, failing with one line per problem:
- every reference archive (results/*.h5 that git tracks) has a gallery section whose recorded
  digest matches the archive's answers and which lists, with a thumbnail and a sentence, every
  figure tools/plot draws for it; the thumbnails stay within tools/plot's size budget;
- tools/plot draws every figure of every archive, and the comparison of the gallery, with
  Python warnings turned into errors, and each figure passes tools/plot's check_figure: legends
  outside the axes, no two series with the same colour and style, a column width, and one
  colour per algorithm across the figures of an archive;
- check_figure itself reports a legend inside the axes and two alike series (so the checks
  above can fail);
- PDFs embed their fonts as TrueType (Type 42), not Type 3;
- bad input (a missing file, a file that is not HDF5, an archive missing a dataset, an archive
  with no algorithms) exits non-zero with a message naming the file, and no traceback.
Figures are drawn at a low resolution to keep the suite fast; what is checked does not depend
on it.
"""
import importlib.machinery
import importlib.util
import os
import re
import subprocess
import sys
import tempfile
import time
import warnings

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
PLOT = os.path.join(ROOT, "tools", "plot")
RESULTS = os.path.join(ROOT, "results")
GALLERY = os.path.join(RESULTS, "figures", "README.md")

loader = importlib.machinery.SourceFileLoader("gjklab_plot", PLOT)
spec = importlib.util.spec_from_loader("gjklab_plot", loader)
plot = importlib.util.module_from_spec(spec)
loader.exec_module(plot)

import h5py  # noqa: E402  (after tools/plot, which says which package is missing)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Warnings become errors here, after the imports, rather than with `python3 -W error`: with
# -W on the command line, Debian's pyparsing switches on its grammar diagnostics and warns about
# matplotlib's own mathtext grammar, which says nothing about these figures.
warnings.simplefilter("error")

problems = []


def fail(message):
    problems.append(message)
    print(f"FAIL {message}", flush=True)


def check_gallery(archives):
    if not os.path.isfile(GALLERY):
        fail(f"{GALLERY}: missing; run tools/plot --gallery")
        return
    with open(GALLERY) as f:
        page = f.read()
    marks = {}
    for m in re.finditer(r"<!-- (archive|compare) (.*?) figures ([\w ]+) -->", page):
        marks.setdefault(m.group(1), []).append((m.group(2).split(), m.group(3).split(), m.start()))
    folders = set()
    by_path = {words[0]: (words, figures, at) for words, figures, at in marks.get("archive", [])}
    for path in archives:
        rel = os.path.relpath(path, ROOT)
        arch = plot.Archive(path)
        if rel not in by_path:
            fail(f"{GALLERY}: no section for {rel}; run tools/plot --gallery")
            continue
        words, figures, _ = by_path[rel]
        if words[1:] != ["digest", arch.digest()]:
            fail(f"{GALLERY}: the section of {rel} was drawn from other answers "
                 f"(recorded {' '.join(words[2:])}, archive {arch.digest()}); run tools/plot --gallery")
        expected = plot.planned(arch)
        if figures != expected:
            fail(f"{GALLERY}: {rel} lists figures {figures}, tools/plot draws {expected}")
        check_entries(page, arch.stem, expected, f"tools/plot {rel}")
        folders.add(arch.stem)
    for words, figures, _ in marks.get("compare", []):
        a, b = words[0], words[1]
        if not (os.path.isfile(os.path.join(ROOT, a)) and os.path.isfile(os.path.join(ROOT, b))):
            fail(f"{GALLERY}: compares {a} and {b}, which are not both present")
            continue
        digests = [plot.Archive(os.path.join(ROOT, p)).digest() for p in (a, b)]
        if words[2:] != ["digest"] + digests:
            fail(f"{GALLERY}: the comparison of {a} and {b} was drawn from other answers")
        runs = plot.compare_runs(os.path.join(ROOT, a), os.path.join(ROOT, b))
        expected = plot.planned(runs[0][1], compare=True)
        folder = f"compare_{runs[0][1].stem}_{runs[1][1].stem}"
        if figures != expected:
            fail(f"{GALLERY}: {folder} lists figures {figures}, tools/plot draws {expected}")
        check_entries(page, folder, expected, f"tools/plot --compare {a} {b}")
        folders.add(folder)
    thumbs = os.path.join(RESULTS, "figures", "gallery")
    total = 0
    for folder in sorted(os.listdir(thumbs)) if os.path.isdir(thumbs) else []:
        for name in os.listdir(os.path.join(thumbs, folder)):
            total += os.path.getsize(os.path.join(thumbs, folder, name))
            if folder not in folders or f"(gallery/{folder}/{name})" not in page:
                fail(f"{thumbs}/{folder}/{name}: a thumbnail the gallery does not show")
    if total > plot.GALLERY_BUDGET:
        fail(f"{thumbs}: {total} bytes of thumbnails, over the budget of {plot.GALLERY_BUDGET}")
    print(f"gallery: {len(folders)} sections, {total} bytes of thumbnails", flush=True)


def check_entries(page, folder, figures, command):
    """Each figure: a heading, its thumbnail (present on disk), a sentence; the section names
    the command that draws them."""
    start = page.find(f"## {folder}\n")
    end = page.find("\n## ", start + 1)
    body = page[start:end if end > 0 else len(page)]
    if start < 0:
        fail(f"{GALLERY}: no heading for {folder}")
        return
    if f"`{command}`" not in body:
        fail(f"{GALLERY}: section {folder} does not give its command `{command}`")
    for name in figures:
        image = f"gallery/{folder}/{name}.png"
        m = re.search(rf"### {re.escape(folder)}/{name}\n\n!\[[^\]]*\]\({re.escape(image)}\)\n\n(.+)\n", body)
        if not m:
            fail(f"{GALLERY}: {folder}/{name} has no heading, thumbnail and sentence")
        elif not m.group(1).strip().endswith("."):
            fail(f"{GALLERY}: {folder}/{name}: the description is not a sentence")
        if not os.path.isfile(os.path.join(RESULTS, "figures", image)):
            fail(f"{GALLERY}: {image} is missing")


def check_drawing(archives, out):
    for path in archives:
        started = time.time()
        try:
            arch = plot.Archive(path)
            made = plot.draw_all([(arch.stem, arch)], os.path.join(out, arch.stem), dpi=30,
                                 formats=("png",), check=True, colours={})
            names = [n for n, _ in made]
            if names != plot.planned(arch):
                fail(f"{path}: drew {names}, planned {plot.planned(arch)}")
            empty = [n for n, caption in made if not caption.strip()]
            if empty:
                fail(f"{path}: figures without a description: {empty}")
        except (plot.PlotError, Warning) as e:
            fail(f"{path}: {type(e).__name__}: {e}")
        except Exception as e:  # a crash of tools/plot is a failure of this check, with its cause
            fail(f"{path}: tools/plot crashed: {type(e).__name__}: {e}")
        plt.close("all")
        print(f"drawn {os.path.relpath(path, ROOT)} in {time.time() - started:.1f} s", flush=True)
    for a, b in plot.GALLERY_COMPARISONS:
        pa, pb = (os.path.join(RESULTS, f"{n}.h5") for n in (a, b))
        if pa in archives and pb in archives:
            try:
                runs = plot.compare_runs(pa, pb)
                plot.draw_all(runs, os.path.join(out, "compare"), dpi=30, formats=("png",),
                              check=True, colours={})
            except (plot.PlotError, Warning) as e:
                fail(f"--compare {a} {b}: {type(e).__name__}: {e}")


def check_the_check():
    """check_figure must see what it is there to see."""
    fig, ax = plt.subplots(figsize=(plot.COLUMN["single"], 2))
    for label in ("one", "two"):
        plot.series(ax.plot([0, 1], [0, 1], color="#1f77b4", label=label)[0], label)
    ax.legend(loc="upper left")
    found = " ".join(plot.check_figure(fig))
    plt.close(fig)
    for expected in ("overlaps the axes", "share colour and style"):
        if expected not in found:
            fail(f"check_figure missed '{expected}' (it said: {found or 'nothing'})")
    fig, ax = plt.subplots(figsize=(5, 2))
    plot.series(ax.plot([0, 1], [0, 1], color="#1f77b4", label="one")[0], "one")
    plot.series(ax.plot([0, 1], [1, 0], color="#ff7f0e", label="two")[0], "two")
    plot.legend_right(ax)
    found = plot.check_figure(fig)
    plt.close(fig)
    if len(found) != 1 or "column width" not in found[0]:
        fail(f"check_figure on a 5-inch figure with an outside legend said {found}")


def check_pdf_fonts(archive, out):
    arch = plot.Archive(archive)
    plot.draw_all([(arch.stem, arch)], out, dpi=30, formats=("pdf",), only=["iterations"])
    with open(os.path.join(out, "iterations.pdf"), "rb") as f:
        pdf = f.read()
    if b"/FontFile2" not in pdf or b"/Type3" in pdf:
        fail(f"{out}/iterations.pdf: fonts are not embedded as TrueType")


def check_bad_input(tmp):
    text = os.path.join(tmp, "notes.h5")
    with open(text, "w") as f:
        f.write("not an archive\n")

    def archive(name, labels, with_rel_error=True):
        path = os.path.join(tmp, name)
        with h5py.File(path, "w") as f:
            f.attrs["experiment_name"] = "bad"
            f.attrs["algorithm_names"] = labels
            f.attrs["family_names"] = ["f"]
            f.attrs["complete"] = np.uint8(1)
            for key, value in (("case_id", np.arange(3, dtype=np.uint64)),
                               ("family", np.zeros(3, np.uint32)), ("size", np.ones(3))):
                f[f"cases/{key}"] = value
            for label in labels:
                g = f.create_group(f"algorithms/{label}")
                g["iterations"] = np.ones(3, np.int32)
                g["boolean_correct"] = np.ones(3, bool)
                g["termination"] = np.zeros(3, h5py.enum_dtype({"converged": 0}, basetype="u1"))
                if with_rel_error:
                    g["rel_error"] = np.zeros(3)
        return path

    cases = [
        ([os.path.join(tmp, "absent.h5")], "no such file"),
        ([text], "not an HDF5 archive"),
        ([archive("missing.h5", ["gjk-johnson"], with_rel_error=False)],
         "missing dataset /algorithms/gjk-johnson/rel_error"),
        ([archive("empty.h5", [])], "has no algorithms"),
        (["--compare", text, text], "not an HDF5 archive"),
    ]
    for args, message in cases:
        run = subprocess.run([sys.executable, PLOT, *args, "--out", os.path.join(tmp, "out")],
                             capture_output=True, text=True)
        named = args[-1]
        if run.returncode == 0 or message not in run.stderr or named not in run.stderr \
                or "Traceback" in run.stderr:
            fail(f"tools/plot {' '.join(args)}: exit {run.returncode}, stderr {run.stderr.strip()!r}; "
                 f"expected a non-zero exit and '{named}: … {message}'")


def main():
    started = time.time()
    archives = plot.reference_archives(RESULTS)
    if not archives:
        fail(f"{RESULTS}: no reference archives")
    check_the_check()
    with tempfile.TemporaryDirectory() as tmp:
        check_bad_input(tmp)
        check_gallery(archives)
        if archives:
            check_pdf_fonts(archives[0], os.path.join(tmp, "pdf"))
        check_drawing(archives, os.path.join(tmp, "png"))
    print(f"plot_check: {len(archives)} archives, {len(problems)} problems, "
          f"{time.time() - started:.0f} s")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
