"""The bag half of `foxglove-bridge --bag`: a bag's topics as Foxglove channels, played with the recorded
timing by `bag play`'s Player, under the app's playback controls (play, pause, speed, seek).

Messages carry their recorded log time and the server's time follows bag time, so the app's timeline
and plots show the recording as it happened. A seek restarts the player from the requested time.
"""

from __future__ import annotations

import threading
from typing import Any

import foxglove
from foxglove.websocket import PlaybackCommand, PlaybackState, PlaybackStatus

from diffctl.bag.player import Player, PlayOptions
from diffctl.bag.reader import Bag, Message


class BagPlayback:
    def __init__(self, bag: Bag, context: foxglove.Context, rate: float = 1.0) -> None:
        self.bag = bag
        self.start_ns = bag.metadata.starting_time_ns
        self.end_ns = bag.metadata.end_ns
        self.rate = rate
        self.server: Any = None
        self._channels: dict[str, foxglove.Channel] = {}
        for topic, ch in bag.channels().items():
            schema = foxglove.Schema(name=ch.type, encoding=ch.schema_encoding, data=ch.schema_text.encode())
            self._channels[topic] = foxglove.Channel(topic, schema=schema, message_encoding=ch.message_encoding,
                                                     context=context)
        self._lock = threading.Lock()
        self._player: Player | None = None
        self._thread: threading.Thread | None = None
        self._position_ns = self.start_ns
        self._paused = True

    @property
    def time_range(self) -> tuple[int, int]:
        return self.start_ns, max(self.end_ns, self.start_ns + 1)

    def _emit(self, msg: Message) -> None:
        self._position_ns = msg.log_time_ns
        self._channels[msg.topic].log(msg.data, log_time=msg.log_time_ns)
        if self.server is not None:
            self.server.broadcast_time(msg.log_time_ns)

    def _start(self, from_ns: int, paused: bool) -> None:
        options = PlayOptions(rate=self.rate, start_offset_s=max(0, from_ns - self.start_ns) / 1e9,
                              start_paused=paused)
        player = Player(lambda f: self.bag.messages(None, f), self.start_ns, options, self._emit)
        self._player = player
        self._thread = threading.Thread(target=self._run, args=(player,), name="foxglove-playback", daemon=True)
        self._thread.start()

    def _run(self, player: Player) -> None:
        player.run()
        if self._player is player and self.server is not None:
            self.server.broadcast_playback_state(
                PlaybackState(PlaybackStatus.Ended, self._position_ns, self.rate, False, ""))

    def start(self, paused: bool = True) -> None:
        with self._lock:
            self._paused = paused
            self._start(self.start_ns, paused)

    def stop(self) -> None:
        with self._lock:
            if self._player is not None:
                self._player.stop()
            if self._thread is not None:
                self._thread.join(2.0)

    def control(self, req: Any) -> PlaybackState:
        """The app's play/pause/speed/seek request → the state after applying it."""
        with self._lock:
            did_seek = req.seek_time is not None
            if req.playback_speed and req.playback_speed > 0:
                self.rate = float(req.playback_speed)
                if self._player is not None:
                    self._player.set_rate(self.rate)
            want_paused = req.playback_command == PlaybackCommand.Pause
            if did_seek:
                if self._player is not None:
                    self._player.stop()
                self._position_ns = int(req.seek_time)
                self._start(self._position_ns, want_paused)
            elif self._player is not None and self._player.timer.paused != want_paused:
                self._player.toggle_pause()
            self._paused = want_paused
            status = PlaybackStatus.Paused if want_paused else PlaybackStatus.Playing
            return PlaybackState(status, self._position_ns, self.rate, did_seek, req.request_id)

    def close(self) -> None:
        self.stop()
        for ch in self._channels.values():
            ch.close()
