"""ament_index_python's resource index and package queries, differential: one program runs under the real
ament_index_python (the Jazzy oracle venv) and under diffctl's overlay, over two install prefixes this test
writes, and every observation (values, exception types and messages, warnings, the `ament_index` command's
output) must be equal."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from tests.oracle import jazzy_venv
from tests.workspace.conftest import write_tree

INDEX = "share/ament_index/resource_index"

PROGRAM = r'''
import contextlib, io, json, os, sys, warnings
import ament_index_python as aip
from ament_index_python.cli import main, resource_name_completer, resource_type_completer

front, back = sys.argv[1], sys.argv[2]
seen = []

def observe(label, call):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            value = call()
            if isinstance(value, dict):
                value = sorted(value.items())
            elif isinstance(value, (set, tuple)):
                value = sorted(value) if isinstance(value, set) else list(value)
            result = ["ok", str(value) if not isinstance(value, (list, bool, str, type(None))) else value]
        except Exception as e:
            result = ["raised", type(e).__name__, isinstance(e, KeyError), isinstance(e, ValueError), str(e)
                      if not isinstance(e, KeyError) else ""]
    seen.append([label, result, [str(w.message) for w in caught]])

def printed(argv):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        returned = main(argv=argv)
    return [out.getvalue(), returned]

def here(packages):
    return {k: v for k, v in packages.items() if k.startswith("ovs_")}

os.environ["AMENT_PREFIX_PATH"] = ""
observe("paths unset", aip.get_search_paths)
observe("types unset", aip.get_resource_types)
os.environ["AMENT_PREFIX_PATH"] = os.pathsep.join([front, os.path.join(front, "missing"), back])
observe("paths", aip.get_search_paths)
observe("types", aip.get_resource_types)
for kind in ("ovs_plugins", "ovs_launchers", "packages", "nothing_here"):
    observe("resources " + kind, lambda: aip.get_resources(kind))
for kind, name in [("ovs_plugins", "ovs_alpha"), ("ovs_plugins", "ovs_beta"), ("ovs_launchers", "ovs_gamma"),
                   ("ovs_plugins", "absent"), ("bad/type", "x"), ("ovs_plugins", "bad\\name"),
                   ("ovs_plugins", "/abs/path"), ("ovs_plugins", "ovs_empty")]:
    observe("get " + kind + " " + name, lambda: aip.get_resource(kind, name))
    observe("has " + kind + " " + name, lambda: aip.has_resource(kind, name))
observe("resources bad", lambda: aip.get_resources("a\\b"))
observe("issubclass", lambda: [issubclass(aip.PackageNotFoundError, KeyError),
                               issubclass(aip.InvalidResourceNameError, ValueError),
                               issubclass(aip.InvalidResourceTypeNameError, ValueError)])
observe("subfolder", lambda: aip.RESOURCE_INDEX_SUBFOLDER)
for name in ("ovs_alpha", "ovs_beta", "ovs_hollow", "ovs_nowhere", "_bad", "bad name", "bad.name", "ok\n"):
    observe("prefix " + name, lambda: aip.get_package_prefix(name))
    observe("share " + name, lambda: aip.get_package_share_directory(name))
    observe("share quiet " + name, lambda: aip.get_package_share_directory(name, print_warning=False))
    observe("share path " + name, lambda: aip.get_package_share_path(name))
observe("with prefixes", lambda: here(aip.get_packages_with_prefixes()))
for argv in ([], ["ovs_plugins"], ["ovs_plugins", "ovs_alpha"], ["ovs_plugins", "ovs_empty"],
             ["packages", "ovs_nowhere"]):
    observe("cli " + " ".join(argv), lambda: printed(argv))
observe("complete types", lambda: sorted(resource_type_completer("ovs_")))
class Parsed:
    resource_type = "ovs_plugins"
observe("complete names", lambda: sorted(resource_name_completer("ovs_a", Parsed)))
Parsed.resource_type = None
observe("complete no type", lambda: sorted(resource_name_completer("ovs_", Parsed)))
print(json.dumps(seen))
'''


def _prefixes(root: Path) -> tuple[Path, Path]:
    front = write_tree(root / "front", {
        f"{INDEX}/packages/ovs_alpha": "",
        f"{INDEX}/packages/ovs_hollow": "",  # indexed, but no share folder
        "share/ovs_alpha/package.xml": "<package/>",
        f"{INDEX}/ovs_plugins/ovs_alpha": "alpha from front",
        f"{INDEX}/ovs_plugins/ovs_empty": "",
        f"{INDEX}/ovs_plugins/.hidden": "x",
        f"{INDEX}/ovs_plugins/folder/inside": "x",
        f"{INDEX}/.hidden_type/x": "x",
    })
    back = write_tree(root / "back", {
        f"{INDEX}/packages/ovs_alpha": "",
        f"{INDEX}/packages/ovs_beta": "",
        "share/ovs_alpha/package.xml": "<package/>",
        "share/ovs_beta/package.xml": "<package/>",
        f"{INDEX}/ovs_plugins/ovs_alpha": "alpha from back",
        f"{INDEX}/ovs_plugins/ovs_beta": "beta\nover two lines",
        f"{INDEX}/ovs_launchers/ovs_gamma": "gamma",
    })
    return front, back


def test_resource_index_and_packages_as_ament_index_python(tmp_path: Path) -> None:
    front, back = _prefixes(tmp_path)
    args = [str(front), str(back)]
    oracle = jazzy_venv.run_python(f"import sys; sys.argv[1:] = {args!r}\n" + PROGRAM)
    env = {k: v for k, v in os.environ.items() if k not in ("DIFFCTL_WORKSPACE", "COLCON_PREFIX_PATH")}
    ours = subprocess.run([sys.executable, "-c", PROGRAM, *args], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=120)
    assert ours.returncode == 0, ours.stderr
    want, got = json.loads(oracle.stdout.splitlines()[-1]), json.loads(ours.stdout.splitlines()[-1])
    diffs = [f"{a[0]}:\n  ament: {a[1:]}\n  ours:  {b[1:]}" for a, b in zip(want, got, strict=True) if a != b]
    assert not diffs, "\n".join(diffs)
