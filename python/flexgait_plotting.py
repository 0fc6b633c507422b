"""Shared helpers of the plotting scripts: CSV reading and atomic PNG writing (matplotlib, Agg)."""
import csv
import os

import matplotlib

from atomic_write import temporary_beside

matplotlib.use("Agg")


def read_rows(path):
    """The rows of a CSV file as dictionaries."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save_atomic(fig, run_dir, name, dpi=100):
    """Writes the figure to RUN_DIR/NAME through a temporary file and a rename."""
    with temporary_beside(run_dir, name) as tmp:
        fig.savefig(tmp, dpi=dpi, format=os.path.splitext(name)[1][1:] or "png")
