"""Where a run's files are, and how a history.h5 is opened without disturbing the run writing it.

A run directory holds history.h5 and particles.pvd; every reader accepts the directory or the file
itself, so that a user can pass whichever is at hand.
"""
from contextlib import contextmanager
from pathlib import Path


class RunFileError(ValueError):
    """A path that is not (or does not hold) the mpile output asked for. The message names the path."""


def history_path(path):
    """The history.h5 of a run directory, or `path` itself when it is a file."""
    path = Path(path)
    if path.is_dir():
        path = path / "history.h5"
        if not path.is_file():
            raise RunFileError(f"{path.parent} holds no history.h5 (is it an mpile output directory?)")
        return path
    if not path.exists():
        raise RunFileError(f"{path}: no such file or directory")
    return path


def snapshots_path(path, collection="particles.pvd"):
    """The `collection` (particles.pvd, or grid.pvd) of a run directory, or `path` itself when it is
    a file (.pvd or one .vtu / .vtr)."""
    path = Path(path)
    if path.is_dir():
        path = path / collection
        if not path.is_file():
            hint = (" (written with [output] grid_snapshots = true)" if collection == "grid.pvd"
                    else " (is it an mpile output directory?)")
            raise RunFileError(f"{path.parent} holds no {collection}{hint}")
        return path
    if not path.exists():
        raise RunFileError(f"{path}: no such file or directory")
    return path


@contextmanager
def read_only(path):
    """The HDF5 file at `path`, open read-only and without HDF5's file lock.

    A run appends to its history.h5 while it goes on; the lock would make the reader fail (or the
    writer, if the reader held it). Reading without it is safe because the writer only appends and
    flushes whole rows; the file is closed as soon as the block ends, so that a later open sees the
    rows written since. h5py older than 3.5 has no `locking` argument: HDF5_USE_FILE_LOCKING=FALSE
    in the environment does the same there.
    """
    import h5py

    try:
        try:
            handle = h5py.File(path, "r", locking=False)
        except TypeError:  # h5py < 3.5
            handle = h5py.File(path, "r")
    except OSError as error:
        raise RunFileError(f"{path} is not a readable HDF5 file ({error})") from None
    try:
        yield handle
    except OSError as error:
        # HDF5 refuses a chunk whose Fletcher32 checksum does not match (mpile writes one on every
        # chunk): data damaged on disk, not numbers to read back.
        raise RunFileError(f"{path}: damaged data, it cannot be read ({error})") from None
    finally:
        handle.close()


def text(value):
    """An HDF5 string attribute as str (h5py returns bytes for fixed-length strings)."""
    if isinstance(value, bytes):
        return value.decode()
    return str(value)


def plain(value):
    """An HDF5 attribute as a plain Python value: str, float, int or a list of them."""
    import numpy as np

    if isinstance(value, (bytes, str)):
        return text(value)
    if isinstance(value, np.ndarray):
        return [plain(v) for v in value.tolist()] if value.ndim else plain(value.item())
    if isinstance(value, np.generic):
        return value.item()
    return value


def units_of(node):
    """The unit attribute of a dataset or group: `units` (the CF convention, current files) or
    `unit` (files written before it was renamed); "" when it has neither."""
    for key in ("units", "unit"):
        if key in node.attrs:
            return text(node.attrs[key])
    return ""

