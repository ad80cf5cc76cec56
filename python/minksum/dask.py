"""Batches of Minkowski sums on a Dask cluster.

One machine runs ``minksum.minkowski_sum_many`` on its cores; when that is not
enough, ``minkowski_sum_many(client, pairs)`` cuts the pairs into chunks and
maps the chunks over the workers of a ``distributed.Client``, each worker
calling ``minksum.minkowski_sum_many`` on its chunk (with its own threads).
The results come back in input order and are exactly the ones a single
process computes: every method is exact and deterministic.

    from distributed import Client, LocalCluster
    import minksum, minksum.dask

    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        sums = minksum.dask.minkowski_sum_many(client, [("cube", "sphere:3"), ("tetra", "random:200:1")])

The workers need minksum importable (the same build).  Operands given as
names (file paths, catalog specs) are sent as text and loaded on the
workers; a file path must then name a file the workers can read.  Polytope
operands are pickled (their exact coordinates and facets) and sent along.
"""

from __future__ import annotations

from typing import Any, Iterable, List, Optional, Sequence

from ._minksum import minkowski_sum_many as _local_many

__all__ = ["minkowski_sum_many", "chunks"]


def chunks(items: Sequence[Any], size: int) -> List[Sequence[Any]]:
    """``items`` cut into consecutive slices of ``size`` (the last may be shorter)."""
    if size < 1:
        raise ValueError("chunk size must be at least 1")
    return [items[i:i + size] for i in range(0, len(items), size)]


def _run_chunk(pairs, start, threads, method):
    """One task: the pairs ``start``, ``start + 1``, ... of the whole batch, failures returned in place.

    The note ``minkowski_sum_many`` gives a failing pair names its index in the
    chunk; it is replaced with one naming the pair's index in the batch.
    """
    out = _local_many(pairs, threads=threads, method=method, on_error="return")
    for k, r in enumerate(out):
        if isinstance(r, BaseException):
            notes = getattr(r, "__notes__", [])
            local = f"minksum.minkowski_sum_many: pairs[{k}]"
            if local in notes:
                notes.remove(local)
            r.add_note(f"minksum.dask.minkowski_sum_many: pairs[{start + k}]")
    return out


def minkowski_sum_many(client, pairs: Iterable[Any], *, chunk_size: Optional[int] = None,
                       threads: Optional[int] = None, method: str = "auto",
                       on_error: str = "raise") -> list:
    """The sums of ``pairs`` computed on the workers of ``client``, in input order.

    pairs, method, on_error: as for ``minksum.minkowski_sum_many``.
    chunk_size: pairs per task (default: the pairs spread over four tasks per
    worker, so that a slow chunk does not leave the other workers idle).
    threads: the threads each worker's ``minkowski_sum_many`` uses (None: one
    per core of the worker; with several single-threaded workers per
    machine, 1).  A failing pair's exception has a note naming its index in
    ``pairs`` ("minksum.dask.minkowski_sum_many: pairs[15]"), whether it is
    raised (on_error="raise": the first failing pair's) or returned in its
    place (on_error="return").
    """
    if on_error not in ("raise", "return"):
        raise ValueError(f"on_error must be 'raise' or 'return', not {on_error!r}")
    pairs = list(pairs)
    if not pairs:
        return []
    if chunk_size is None:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        chunk_size = max(1, -(-len(pairs) // (4 * workers)))
    parts = chunks(pairs, chunk_size)
    starts = range(0, len(pairs), chunk_size)
    futures = client.map(_run_chunk, parts, starts, threads=threads, method=method, pure=False)
    out: list = []
    for part in client.gather(futures):
        out.extend(part)
    if on_error == "raise":
        for r in out:
            if isinstance(r, BaseException):
                raise r
    return out
