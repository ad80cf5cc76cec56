"""minksum.dask: a batch mapped over a LocalCluster of two worker processes equals the single-process batch exactly."""

import pytest

import minksum

pytestmark = pytest.mark.dask


def summary(s):
    return (s.method, s.exact_vertices(), s.planes(), s.vertex_origin.tolist(), s.facet_provenance)


def test_local_cluster_two_workers_equals_one_process(data):
    distributed = pytest.importorskip("distributed")
    import minksum.dask

    specs = ["cube", "tetra", "sphere:2@rot:4", "random:40:5", "dodecahedron"]
    pairs = [(a, b) for a in specs for b in specs]
    pairs += [(minksum.load("box:1:1/3:1/7"), minksum.load("sphere:1@rot:2"))]  # pickled polytopes
    expected = [summary(s) for s in minksum.minkowski_sum_many(pairs, threads=1)]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        got = minksum.dask.minkowski_sum_many(client, pairs, chunk_size=4, threads=1)
        assert [summary(s) for s in got] == expected
        bad = str(data / "bad" / "nan.off")
        with pytest.raises(minksum.InputError) as e:
            minksum.dask.minkowski_sum_many(client, [("cube", "tetra"), ("cube", bad)], chunk_size=1)
        assert e.value.file == bad and any("pairs[1]" in n for n in e.value.__notes__)
        # on_error="return": the failing pair's exception, back from its worker, names its index in the batch.
        many = [("cube", "tetra")] * 15 + [("cube", bad)] + [("cube", "tetra")] * 4
        out = minksum.dask.minkowski_sum_many(client, many, chunk_size=4, on_error="return")
        assert [i for i, r in enumerate(out) if not isinstance(r, minksum.Sum)] == [15]
        assert out[15].file == bad and out[15].__notes__ == ["minksum.dask.minkowski_sum_many: pairs[15]"]
        # solids and sweeps: every kind of result comes back from the workers exactly
        mixed = [("tube", "cube@scale:1/8"), ("lshape", minksum.load("sphere:1@scale:1/4")),
                 ("cube", "segment:0,0,0:3,1,2"), ("segment:0,0,0:2,0,0", minksum.ConvexSet.load("square")),
                 (minksum.Solid.load("ring:6"), "tetra@scale:1/8")]
        local = minksum.minkowski_sum_many(mixed, threads=1)
        remote = minksum.dask.minkowski_sum_many(client, mixed, chunk_size=2, threads=1)
        assert [type(r).__name__ for r in remote] == [type(r).__name__ for r in local]
        assert [r.volume() for r in remote] == [r.volume() for r in local]
        assert [sorted(r.exact_vertices()) for r in remote] == [sorted(r.exact_vertices()) for r in local]


def test_chunks():
    import minksum.dask

    assert minksum.dask.chunks(list(range(7)), 3) == [[0, 1, 2], [3, 4, 5], [6]]
    with pytest.raises(ValueError):
        minksum.dask.chunks([1], 0)


def test_docs_dask_example():
    # The Dask block of docs/python.md, run as a script (its LocalCluster under `if __name__ == "__main__"`).
    from test_docs import python_blocks

    (code,) = [b for b in python_blocks("docs/python.md") if "LocalCluster" in b]
    namespace = {"__name__": "__main__"}
    exec(compile(code, "docs/python.md", "exec"), namespace)
    sums = namespace["sums"]
    assert len(sums) == 100
    assert [s.volume() for s in sums[:3]] == [minksum.minkowski_sum(f"random:200:{i}", "sphere:3").volume() for i in range(3)]


class InProcessClient:
    """What minksum.dask uses of a distributed.Client, run in this process (no cluster)."""

    def __init__(self, workers=2):
        self.workers = workers
        self.tasks = []

    def scheduler_info(self):
        return {"workers": {f"w{i}": {} for i in range(self.workers)}}

    def map(self, fn, *iterables, pure=True, **kwargs):
        self.tasks = [fn(*args, **kwargs) for args in zip(*iterables)]
        return self.tasks

    def gather(self, futures):
        return list(futures)


def test_dask_error_names_global_pair_index(data):
    # Pair 15 fails; in chunks of 4 it is pair 3 of the fourth chunk: its note must say pairs[15].
    import minksum.dask

    bad = str(data / "bad" / "nan.off")
    pairs = [("cube", "tetra")] * 15 + [("cube", bad), ("tetra", "nosuch")] + [("cube", "tetra")] * 3
    client = InProcessClient()
    out = minksum.dask.minkowski_sum_many(client, pairs, chunk_size=4, on_error="return")
    assert len(client.tasks) == 5
    assert [i for i, r in enumerate(out) if not isinstance(r, minksum.Sum)] == [15, 16]
    assert isinstance(out[15], minksum.InputError) and out[15].file == bad
    assert out[15].__notes__ == ["minksum.dask.minkowski_sum_many: pairs[15]"]
    assert isinstance(out[16], ValueError) and out[16].__notes__ == ["minksum.dask.minkowski_sum_many: pairs[16]"]
    with pytest.raises(minksum.InputError) as e:
        minksum.dask.minkowski_sum_many(InProcessClient(), pairs, chunk_size=4)
    assert e.value.__notes__ == ["minksum.dask.minkowski_sum_many: pairs[15]"]
    # The default chunk size (the pairs over four tasks per worker): the same indices.
    out = minksum.dask.minkowski_sum_many(InProcessClient(workers=3), pairs, on_error="return")
    assert out[15].__notes__ == ["minksum.dask.minkowski_sum_many: pairs[15]"]
    assert out[16].__notes__ == ["minksum.dask.minkowski_sum_many: pairs[16]"]
