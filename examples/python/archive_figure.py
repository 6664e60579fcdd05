#!/usr/bin/python3
"""A figure from a results archive with pandas: each algorithm's distance error, per family.

Reads the archive of `gjklab run` (or gjklab.run) with gjklab.read_archive and draws, for every
algorithm that reports a distance, the share of cases whose error relative to the pair's size
is above x, on log-log axes so that the rare large errors stay visible (peer libraries dashed).
Also prints the worst error per algorithm and family.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/archive_figure.py \\
        results/real_objects.h5 real_objects.png
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import gjklab

# Errors below this are drawn at it (log axis; exact answers have error 0).
FLOOR = 1e-18


def errors(archive):
    """One row per (case, algorithm) with a distance: family, algorithm, relative error."""
    frames = []
    order = archive.attrs.get("algorithm_names", list(archive.algorithms))
    for name in order:
        frame = archive.algorithms[name]
        if frame["distance"].isna().all():
            continue  # boolean-only algorithm
        frames.append(pd.DataFrame({"family": archive.cases["family"], "algorithm": name,
                                    "rel_error": frame["rel_error"]}))
    return pd.concat(frames, ignore_index=True).dropna(subset=["rel_error"])


def draw(table, title, path):
    peers = {name for name, info in gjklab.algorithms().items() if info["peer"]}
    colours = plt.get_cmap("tab20").colors
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, (name, group) in enumerate(table.groupby("algorithm", sort=False)):
        x = np.sort(np.maximum(group["rel_error"].to_numpy(), FLOOR))
        above = 1.0 - np.arange(len(x)) / len(x)  # share of cases with error >= x[i]
        ax.step(x, above, where="post", label=name, color=colours[k % len(colours)],
                linestyle="--" if name in peers else "-")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("distance error / pair size (errors below 1e-18 drawn at 1e-18)")
    ax.set_ylabel("share of cases with a larger error")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=1, loc="center left", bbox_to_anchor=(1.01, 0.5))
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("archive")
    parser.add_argument("figure", help="output image (.png, .svg, .pdf)")
    args = parser.parse_args()
    archive = gjklab.read_archive(args.archive)
    table = errors(archive)
    worst = table.pivot_table(index="algorithm", columns="family", values="rel_error",
                              aggfunc="max", observed=True, sort=False)
    with pd.option_context("display.width", 150, "display.float_format", "{:.2g}".format):
        print("largest distance error / size:")
        print(worst.to_string())
    draw(table, f"{archive.attrs.get('experiment_name', args.archive)}: "
                f"{len(archive.cases)} cases", args.figure)
    print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()
