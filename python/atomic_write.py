"""Files that appear whole or not at all, named as the C++ side names its temporaries.

A temporary is ".NAME.tmp-PID-XXXXXXXX" beside the target (PID: the writing process), so that
flexgait's RunDirectory can remove the ones a killed writer left behind (their process is gone)
without touching a live writer's (core/atomic_file.hpp, remove_orphaned_temporaries).
"""
import contextlib
import os
import tempfile


@contextlib.contextmanager
def temporary_beside(directory, name):
    """Yields the path of a new temporary file in DIRECTORY; on leaving the block without an
    exception it is made world-readable (0644, as the C++ side's files are: mkstemp creates 0600)
    and renamed to DIRECTORY/NAME, otherwise removed."""
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{name}.tmp-{os.getpid()}-")
    os.close(fd)
    try:
        yield tmp
        os.chmod(tmp, 0o644)
        os.replace(tmp, os.path.join(directory, name))
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_text_atomic(directory, name, text):
    """Writes TEXT (UTF-8) to DIRECTORY/NAME atomically."""
    with temporary_beside(directory, name) as tmp:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
