"""rhabel.solve releases the GIL: two threads solve scenes concurrently with the same results as
one after the other. No wall-clock assertion: the GIL release is observed by the logic of the
interpreter (with an infinite switch interval a thread that holds the GIL is never preempted)."""

import math
import sys
import threading

import numpy as np

import rhabel
from conftest import SOURCE_DIR, parabola_scene


def comparable(result):
    """The result without its wall time (everything else is deterministic)."""
    plain = result.to_plain()
    plain["diagnostics"].pop("seconds")
    return plain


def scenes():
    default = rhabel.load_scene(SOURCE_DIR / "examples" / "default_scene.json")
    return [default] + [parabola_scene(alpha=alpha, coulomb=0.5, nu=0.3) for alpha in (0.0, 0.25, 0.6)]


def test_two_threads_give_the_sequential_results():
    todo = scenes()
    expected = [comparable(rhabel.solve(s, grid=50)) for s in todo]
    results = {}
    barrier = threading.Barrier(2)

    def work(name, order):
        barrier.wait()
        for _ in range(3):
            for i in order:
                results.setdefault(name, []).append((i, comparable(rhabel.solve(todo[i], grid=50))))

    threads = [threading.Thread(target=work, args=("forward", list(range(len(todo))))),
               threading.Thread(target=work, args=("backward", list(reversed(range(len(todo))))))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for name in ("forward", "backward"):
        assert len(results[name]) == 3 * len(todo)
        for i, got in results[name]:
            assert got == expected[i], f"{name}: scene {i} differs from the sequential solve"


def test_solve_lets_other_threads_run():
    """With an infinite switch interval the interpreter never takes the GIL from a running
    thread; the worker below runs pure Python until it enters rhabel.solve. So the main thread
    runs again before the worker's first solve has returned only if the solve released the GIL.
    (If it did not, `first_done` would already be set when Thread.start() returns.)"""
    scene = rhabel.load_scene(SOURCE_DIR / "examples" / "default_scene.json")
    first_done = threading.Event()
    out = []

    def worker():
        out.append(rhabel.solve(scene, grid=400))  # a coupled scene: tens of milliseconds in C++
        first_done.set()
        out.append(rhabel.solve(scene, grid=400))

    previous = sys.getswitchinterval()
    sys.setswitchinterval(1e3)
    try:
        t = threading.Thread(target=worker)
        t.start()  # returns once the worker has started; the worker then keeps the GIL until it releases it
        ran_during_solve = not first_done.is_set()
        t.join()
    finally:
        sys.setswitchinterval(previous)
    assert len(out) == 2 and comparable(out[0]) == comparable(out[1])
    assert ran_during_solve, "the main thread could not run while rhabel.solve was computing: GIL held"


def test_solvers_with_python_callables_in_two_threads():
    """The Abel solvers call Python back from C++ without the GIL held in between: two threads,
    each with its own callable, give the sequential results."""
    def run(c):
        f = lambda s: math.exp(c * s)  # noqa: E731
        sol = rhabel.abel.solve(0.3, 0.1, -1.0, 1.0, "bounded", "unbounded", f)
        rh = rhabel.riemann.solve_abel_rh(0.3, 0.1, -1.0, 1.0, f, "bounded", "unbounded")
        y = np.linspace(-0.9, 0.9, 7)
        return sol.density(y).tolist(), sol.residual, rh.total(), rh.density(y)[0].tolist()

    constants = [0.5, -1.0, 2.0]
    expected = [run(c) for c in constants]
    got = {}

    def work(name):
        got[name] = [run(c) for c in constants for _ in range(2)]

    threads = [threading.Thread(target=work, args=(name,)) for name in ("first", "second")]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for name in ("first", "second"):
        assert got[name] == [e for e in expected for _ in range(2)], name
