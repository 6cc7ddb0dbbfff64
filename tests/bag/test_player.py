"""Playback timing with a fake clock: recorded pace, rate, start offset, pause/step, loop, /clock."""

from __future__ import annotations

import itertools

from diffctl.bag.keys import decode
from diffctl.bag.player import Player, PlayOptions
from diffctl.bag.reader import Message
from diffctl.bag.timing import PlaybackTimer

SEC = 1_000_000_000
T0 = 50 * SEC


class FakeClock:
    def __init__(self) -> None:
        self.t = 100.0

    def now(self) -> float:
        return self.t

    def sleep(self, dt: float) -> None:
        self.t += dt


def bag(offsets_ms: list[int]):
    msgs = [Message("/a", T0 + ms * 1_000_000, 0, 0, b"x") for ms in offsets_ms]
    return lambda from_ns: [m for m in msgs if m.log_time_ns >= from_ns]


def play(offsets_ms: list[int], **opts) -> tuple[list[float], Player]:
    clock = FakeClock()
    out: list[float] = []
    p = Player(bag(offsets_ms), T0, PlayOptions(**opts), lambda m: out.append(round(clock.now() - 100.0, 6)),
               now_s=clock.now, sleep_s=clock.sleep)
    p.run()
    return out, p


def test_recorded_pace_and_rate() -> None:
    assert play([0, 100, 350, 1000])[0] == [0.0, 0.1, 0.35, 1.0]
    assert play([0, 100, 350, 1000], rate=2.0)[0] == [0.0, 0.05, 0.175, 0.5]


def test_start_offset_skips_and_shifts() -> None:
    out, p = play([0, 100, 350, 1000], start_offset_s=0.3)
    assert out == [0.05, 0.7] and p.published == 2


def test_timer_pause_resume_and_rate_change_keep_bag_time_continuous() -> None:
    clock = FakeClock()
    t = PlaybackTimer(T0, 1.0, clock.now)
    clock.sleep(1.0)
    t.pause()
    clock.sleep(5.0)
    assert t.bag_now_ns() == T0 + SEC
    t.resume()
    clock.sleep(0.5)
    t.set_rate(2.0)
    clock.sleep(0.5)
    assert t.bag_now_ns() == T0 + 5 * SEC // 2  # 1 s, paused, 0.5 s at 1x, 0.5 s at 2x
    assert t.wall_at(T0 + 4 * SEC) == clock.now() + 0.75


def test_step_publishes_the_next_message_while_paused() -> None:
    clock = FakeClock()
    out: list[float] = []
    p: Player | None = None

    def sleep(dt: float) -> None:
        clock.sleep(dt)
        assert p is not None
        if clock.now() > 200 and p.published < 2:
            p.step()  # a long time paused: the user presses → twice
        if clock.now() > 300 and p.timer.paused:
            p.toggle_pause()

    p = Player(bag([0, 1000, 2000, 2500]), T0, PlayOptions(start_paused=True),
               lambda m: out.append(clock.now()), now_s=clock.now, sleep_s=sleep)
    p.run()
    assert p.published == 4
    assert 200 <= out[0] <= out[1] < 201  # stepped while paused, not timed (they are 1 s apart in the bag)
    assert 301 <= out[2] < 301.5  # resumed at 300: 1 s of bag time after the stepped-to message
    assert abs(out[3] - out[2] - 0.5) < 1e-6


def test_loop_plays_again() -> None:
    clock = FakeClock()
    out: list[float] = []
    p: Player | None = None

    def publish(m: Message) -> None:
        out.append(clock.now())
        if len(out) == 6:
            assert p is not None
            p.stop()

    p = Player(bag([0, 500]), T0, PlayOptions(loop=True), publish, now_s=clock.now, sleep_s=clock.sleep)
    p.run()
    assert [round(t - 100, 3) for t in out] == [0.0, 0.5, 0.5, 1.0, 1.0, 1.5]


def test_clock_follows_bag_time() -> None:
    import time

    clocks: list[int] = []
    p = Player(bag([0, 300]), T0, PlayOptions(clock_hz=50), lambda m: None, lambda ns: clocks.append(ns))
    p.run()
    time.sleep(0.05)
    assert clocks and clocks[0] >= T0 and all(b >= a for a, b in itertools.pairwise(clocks))
    assert clocks[-1] <= T0 + 2 * SEC


def test_keys() -> None:
    assert decode(b" \x1b[C\x1b[A\x1b[Bq") == ["space", "right", "up", "down"]
