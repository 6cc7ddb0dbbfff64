"""`--print` and `--show-args`: a resolved plan as a process tree, declared arguments as a table.

The tree is deterministic text (the same description written in YAML and in Python prints the same),
built from console.Text so colours go away with --no-color and in tests.
"""

from __future__ import annotations

import shlex
import signal
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import yaml

from diffctl.console import Text, table
from diffctl.launch_legacy import commandline
from diffctl.launch_legacy.parameters import CommandLineParameter
from diffctl.launch_legacy.plan import (
    AddHandler,
    Argument,
    Gate,
    LogMessage,
    Plan,
    ProcessSpec,
    RequestShutdown,
    SignalProcesses,
    Skipped,
    StartProcess,
    StartTimer,
    Step,
    Unknown,
)


@dataclass
class _Node:
    label: Text
    children: list[_Node] = field(default_factory=list)

    def add(self, label: str | Text, style: str = "") -> _Node:
        child = _Node(label if isinstance(label, Text) else Text(label, style=style))
        self.children.append(child)
        return child

    def lines(self, prefix: str = "") -> list[Text]:
        out: list[Text] = []
        for i, child in enumerate(self.children):
            last = i == len(self.children) - 1
            out.append(Text(prefix + ("└── " if last else "├── "), style="dim") + child.label)
            out += child.lines(prefix + ("    " if last else "│   "))
        return out


def short(value: Any, limit: int = 60) -> str:
    """A value as it would be written, long text cut with its length noted (an SDF is thousands of chars)."""
    text = repr(value) if isinstance(value, str) else str(value).lower() if isinstance(value, bool) else repr(value)
    if len(text) <= limit:
        return text
    return text[: limit - 20] + f"…' ({len(value) if isinstance(value, str) else len(text)} chars)"


def _seconds(value: float) -> str:
    return f"{value:g} s"


def _gate(node: _Node, gate: Gate | None) -> None:
    if gate is None:
        return
    text = "wait for: " + "; ".join(w.describe() for w in gate.waits)
    if gate.timeout_s is not None:
        text += f" (timeout {_seconds(gate.timeout_s)})"
    node.add(text, "yellow")


def _flatten(prefix: str, values: dict[str, Any]) -> Iterable[tuple[str, Any]]:
    for key, value in values.items():
        if isinstance(value, dict):
            yield from _flatten(f"{prefix}{key}.", value)
        else:
            yield f"{prefix}{key}", value


def _process(node: _Node, spec: ProcessSpec, gate: Gate | None) -> None:
    p = node.add(Text("process ", style="bold") + Text(spec.name, style="bold cyan"))
    _gate(p, gate)
    p.add("cmd: " + shlex.join(commandline.argv(spec)))
    if spec.cwd:
        p.add(f"cwd: {spec.cwd}")
    if spec.node is not None:
        n = spec.node
        fqn = n.namespace.rstrip("/") + "/" + (n.node_name or "<default name>")
        p.add(f"node: {fqn}")
        for entry in n.params:
            if isinstance(entry, str):
                p.add(f"params file: {entry}")
            elif isinstance(entry, CommandLineParameter):
                p.add(f"param {entry.name} = {short(yaml.safe_load(entry.text))}")
            else:
                for key, value in _flatten("", dict(entry)):
                    p.add(f"param {key} = {short(value)}")
        for src, dst in n.remaps:
            p.add(f"remap: {src} → {dst}")
    if spec.env_replace:
        p.add("env: (replaced entirely)")
    for key in sorted(spec.env):
        value = spec.env[key]
        p.add(f"env: {key}={value}" if value is not None else f"env: unset {key}")
    opts = [f"output {spec.output}"]
    if spec.respawn:
        retries = "no limit" if spec.respawn_max_retries < 0 else f"at most {spec.respawn_max_retries}"
        opts.append(f"respawn after {_seconds(spec.respawn_delay_s)} ({retries})")
    if spec.required:
        opts.append("required (its exit shuts the launch down)")
    if spec.interactive:
        opts.append("interactive (gets the terminal's stdin)")
    opts.append(
        f"stop: SIGINT, SIGTERM after {_seconds(spec.sigterm_timeout_s)}, "
        f"SIGKILL after {_seconds(spec.sigkill_timeout_s)} more"
    )
    p.add("; ".join(opts), "dim")


def _steps(node: _Node, steps: Iterable[Step]) -> None:
    for step in steps:
        if isinstance(step, StartProcess):
            _process(node, step.spec, step.gate)
        elif isinstance(step, StartTimer):
            when = "after ? s" if step.period_s != step.period_s else f"after {_seconds(step.period_s)}"
            t = node.add(Text(when + " (evaluated when it fires)", style="magenta"))
            _gate(t, step.gate)
            _steps(t, step.steps)
        elif isinstance(step, AddHandler):
            h = step.handler
            targets = ", ".join(str(t) for t in h.targets) or "any process"
            label = {
                "exit": f"on exit of {targets}",
                "start": f"on start of {targets}",
                "shutdown": "on shutdown",
                "io": f"on output ({', '.join(h.streams)}) of {targets}",
                "complete": f"on completion of {targets if h.targets else 'any action'}",
                "state": "on a lifecycle state transition",
            }
            text = label.get(h.event, f"on {h.event}") + (
                f" with code {h.exit_code}" if h.exit_code is not None else ""
            )
            if h.callback is not None:
                text += f": calls {h.describe_callback or 'a function'} (its actions are resolved when it fires)"
            elif h.steps:
                text += " (evaluated when it fires; as of now:)"
            child = node.add(Text(text, style="magenta"))
            _gate(child, step.gate)
            _steps(child, h.steps)
        elif isinstance(step, LogMessage):
            _gate(node.add(f"log {step.message!r}"), step.gate)
        elif isinstance(step, SignalProcesses):
            what = signal.Signals(step.signal).name if step.signal is not None else "stop (SIGINT, escalating)"
            _gate(node.add(f"{what} to {', '.join(str(t) for t in step.targets)}", "red"), step.gate)
        elif isinstance(step, RequestShutdown):
            _gate(node.add(f"shutdown {step.reason!r}", "red"), step.gate)
        elif isinstance(step, Skipped):
            node.add(f"skipped ({step.condition}): {step.what}", "dim")
        elif isinstance(step, Unknown):
            node.add(f"known only when it runs: {step.why}", "yellow")


class PlanView:
    """The `--print` output of a plan."""

    def __init__(self, plan: Plan) -> None:
        self.plan = plan

    def lines(self) -> list[Text]:
        out = [Text("launch file: ", style="bold") + Text(self.plan.source)]
        if self.plan.arguments:
            out.append(Text("arguments:", style="bold"))
            for a in self.plan.arguments:
                out.append(
                    Text(
                        f"    {a.name} = {a.value!r}" + (f"  (default {a.default!r})" if a.default is not None else "")
                    )
                )
        out.append(Text(f"actions ({len(self.plan.processes)} processes):", style="bold"))
        root = _Node(Text(""))
        _steps(root, self.plan.steps)
        out += root.lines()
        out += [Text(f"warning: {w}", style="yellow") for w in self.plan.warnings]
        return out

    def __rich__(self) -> Text:
        return Text("\n").join(self.lines())


class ArgumentsView:
    """The `--show-args` table."""

    def __init__(self, arguments: list[Argument]) -> None:
        self.arguments = arguments

    def __rich__(self) -> Any:
        rows = [
            (
                a.name,
                "(required)" if a.default is None else repr(a.default),
                a.description or "",
                ", ".join(a.choices) if a.choices else "",
            )
            for a in self.arguments
        ]
        return table(
            "Arguments (pass arguments as '<name>:=<value>')", ["argument", "default", "description", "choices"], rows
        )
