"""The solve releases the GIL: other Python threads run meanwhile."""

import threading

import cufem
from conftest import EXAMPLES


def test_other_threads_run_during_the_solve():
    model = cufem.Model.from_file(EXAMPLES / "bending_compact_4L9.toml")
    done = []
    worker = threading.Thread(target=lambda: done.append(model.run(threads=1, quiet=True)))
    count = 0
    worker.start()
    while worker.is_alive():
        count += 1
    worker.join()
    assert done[0].summary["status"] == "converged"
    # a solve of ~0.5 s holding the GIL would leave this loop a handful of turns
    assert count > 10_000, count
