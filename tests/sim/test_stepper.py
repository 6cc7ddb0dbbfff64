"""The simulation loop on its own (a counter for physics): task timing, order, step/pause, pacing."""

from __future__ import annotations

import threading
import time

from diffctl.sim.stepper import Stepper

MS = 1_000_000


def make(rtf: float = 0.0, paused: bool = True) -> tuple[Stepper, list[int]]:
    steps: list[int] = []
    st = Stepper(lambda: steps.append(1), MS, rtf=rtf, paused=paused)
    return st, steps


def run_steps(st: Stepper, n: int) -> None:
    done = threading.Event()
    st.step_n(n, done.set)
    st.run(done)


def test_tasks_run_on_their_sim_time_grid_in_order() -> None:
    st, steps = make()
    log: list[tuple[str, int]] = []
    st.add_task("a", 10 * MS, lambda t: log.append(("a", t)))
    st.add_task("b", 25 * MS, lambda t: log.append(("b", t)), first_ns=5 * MS)
    st.add_task("c", 10 * MS, lambda t: log.append(("c", t)), before_others=True)
    run_steps(st, 50)
    assert len(steps) == 50 and st.sim_time_ns == 50 * MS
    at = {t: [n for n, tt in log if tt == t] for _, t in log}
    assert at[0] == ["c", "a"]  # before_others first
    assert [t for n, t in log if n == "a"] == [0, 10 * MS, 20 * MS, 30 * MS, 40 * MS, 50 * MS]
    assert [t for n, t in log if n == "b"] == [5 * MS, 30 * MS]


def test_removed_tasks_stop_and_reset_makes_everything_due() -> None:
    st, _ = make()
    log: list[int] = []
    task = st.add_task("a", 3 * MS, log.append)
    run_steps(st, 7)
    st.remove_task(task)
    run_steps(st, 10)
    assert log == [0, 3 * MS, 6 * MS]
    again = st.add_task("b", 100 * MS, log.append, first_ns=500 * MS)
    st.reset_time()
    assert st.sim_time_ns == 0 and st.stats.iterations == 0 and again.next_ns == 0
    run_steps(st, 1)
    assert log[-1] == 0  # due at once, at sim time 0


def test_pause_resume_and_calls_from_other_threads() -> None:
    st, steps = make(paused=True)
    stop = threading.Event()
    th = threading.Thread(target=st.run, args=(stop,))
    th.start()
    try:
        time.sleep(0.1)
        assert steps == []  # paused: no physics
        st.call_soon(lambda: st.set_paused(False))
        deadline = time.monotonic() + 5
        while len(steps) < 1000 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert len(steps) >= 1000
        st.call_soon(lambda: st.set_paused(True))
        time.sleep(0.1)
        n = len(steps)
        time.sleep(0.1)
        assert len(steps) == n
    finally:
        stop.set()
        th.join(5)


def test_real_time_factor_paces_the_loop() -> None:
    st, _ = make(rtf=5.0, paused=False)
    stop = threading.Event()
    st.add_task("end", 500 * MS, lambda t: stop.set() if t else None)
    t0 = time.perf_counter()
    st.run(stop)
    wall = time.perf_counter() - t0
    # 0.5 s of sim time at 5x real time: never faster than 0.1 s of wall time.
    assert st.sim_time_ns == 500 * MS and wall >= 0.098
