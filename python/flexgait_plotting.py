"""Shared helpers of the plotting scripts: CSV reading and atomic PNG writing (matplotlib, Agg)."""
import csv
import os
import tempfile

import matplotlib

matplotlib.use("Agg")


def read_rows(path):
    """The rows of a CSV file as dictionaries."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save_atomic(fig, run_dir, name, dpi=100):
    """Writes the figure to RUN_DIR/NAME through a temporary file and a rename."""
    fd, tmp = tempfile.mkstemp(dir=run_dir, prefix=f".{name}.", suffix=".png")
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=dpi)
        os.replace(tmp, os.path.join(run_dir, name))
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
