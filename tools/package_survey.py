"""Count what public ROS 2 robot projects start: packages of their launch files, controller types, Gazebo systems.

    python tools/package_survey.py SNAPSHOTS [--repos tools/package_survey_repos.tsv] [--json OUT] [--markdown]

SNAPSHOTS holds one git repository per surveyed project, as `owner+name/repo` (a bare git directory) or
`owner+name` (a checkout). The list names each repository with the commit counted; the files are read from that
commit with git, never from a work tree. Nothing is run: launch files are read as text (Python ones with `ast`),
so a package counts only where the file names it literally or through a variable assigned a literal.

What is counted, per launch file (test folders left out):
- the packages it starts: `Node`/`LifecycleNode`/`ComposableNode…(package=…)`, `<node pkg=…>`, `node: pkg:`,
  `ros2 run PKG` / `ros2 launch PKG` commands, the `xacro` command, `gz sim`/`ign gazebo` commands (as `gz`);
- the launch files it includes: a file of the project's own packages is followed (its packages count for the
  includer), a file of another package counts as that package started (`ros_gz_sim`'s gz_sim.launch.py).
The project's own packages (its package.xml names) are not ranked. Controller types are the `type:` values of
YAML files holding `ros__parameters`; Gazebo systems are the `filename` of `<plugin>` elements in SDF, URDF and
xacro files. Each row says whether diffctl provides the name, read from diffctl itself (its package index,
controller plugins and simulator), so the table follows the code.
"""

from __future__ import annotations

import argparse
import ast
import json
import re
import subprocess
import sys
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

import yaml

SHARE_CALLS = {
    "get_package_share_directory", "get_package_share_path", "get_package_prefix", "FindPackageShare",
    "FindPackagePrefix", "FindPackage",
}
NODE_CALLS = {"Node", "LifecycleNode", "ComposableNode", "ComposableNodeContainer", "RosNode"}
INCLUDE_CALLS = {"IncludeLaunchDescription"}
PROCESS_CALLS = {"ExecuteProcess", "Command"}
FIND_PKG = re.compile(r"\$\(\s*find(?:-pkg-share|-pkg-prefix)?\s+([A-Za-z0-9_]+)\s*\)")
LAUNCH_NAME = re.compile(r"[\w.\-]+\.(?:launch\.py|launch\.xml|launch\.yaml|launch|py|xml|yaml)$")
CONTROLLER_TYPE = re.compile(r"^\s*type\s*:\s*[\"']?([A-Za-z0-9_]+/[A-Za-z0-9_]+)[\"']?\s*(?:#.*)?$", re.M)
PLUGIN_TAG = re.compile(r"<plugin\b([^>]*)>", re.S)
ATTR = re.compile(r"""(\w+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")
HW_PLUGIN = re.compile(r"<hardware>\s*<plugin>\s*([^<\s]+)\s*</plugin>", re.S)
GZ_SYSTEM = re.compile(r"^(?:lib)?(?:gz-sim\d*-|ignition-gazebo\d*-|gz_ros2_control|ign_ros2_control)")
DESCRIPTION_SUFFIXES = (".sdf", ".urdf", ".xacro", ".world", ".gazebo", ".sdf.xacro", ".urdf.xacro")


# ---------------------------------------------------------------------------------------------- reading git


@dataclass
class Snapshot:
    repo: str
    git_dir: Path
    commit: str

    def paths(self) -> list[str]:
        out = subprocess.run(["git", "--git-dir", str(self.git_dir), "ls-tree", "-r", "--name-only", self.commit],
                             capture_output=True, text=True, check=True).stdout
        return out.splitlines()

    def read(self, paths: list[str]) -> dict[str, str]:
        """The text of each path at the commit, through one `git cat-file --batch`."""
        if not paths:
            return {}
        request = "".join(f"{self.commit}:{p}\n" for p in paths).encode()
        raw = subprocess.run(["git", "--git-dir", str(self.git_dir), "cat-file", "--batch"], input=request,
                             capture_output=True, check=True).stdout
        texts: dict[str, str] = {}
        pos = 0
        for p in paths:
            end = raw.index(b"\n", pos)
            header = raw[pos:end].split()
            pos = end + 1
            if len(header) < 3 or header[1] == b"missing":
                continue
            size = int(header[2])
            texts[p] = raw[pos:pos + size].decode("utf-8", "replace")
            pos += size + 1
        return texts


def git_dir_of(snapshots: Path, repo: str) -> Path:
    base = snapshots / repo.replace("/", "+")
    for candidate in (base / "repo", base / ".git", base):
        if (candidate / "HEAD").is_file() and (candidate / "objects").is_dir():
            return candidate
    raise SystemExit(f"{repo}: no git repository under {base} (fetch it first)")


# ------------------------------------------------------------------------------------------ launch files


@dataclass
class Launch:
    path: str
    package: str | None  # the own package holding it
    nodes: set[tuple[str, str]] = field(default_factory=set)  # (package, executable or "?")
    includes: set[tuple[str, str]] = field(default_factory=set)  # (package, launch file name)
    commands: set[str] = field(default_factory=set)  # pseudo-packages: xacro, gz


@dataclass
class Value:
    """What a Python expression of a launch file is known to hold: packages found by share look-ups, literals."""
    packages: set[str] = field(default_factory=set)
    strings: list[str] = field(default_factory=list)

    def __or__(self, other: Value) -> Value:
        return Value(self.packages | other.packages, self.strings + other.strings)


def _call_name(node: ast.Call) -> str:
    f = node.func
    return f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""


class PythonLaunchReader(ast.NodeVisitor):
    """Walks a Python launch file in source order, tracking variables assigned package look-ups and literals."""

    def __init__(self, launch: Launch) -> None:
        self.launch = launch
        self.env: dict[str, Value] = {}

    def value(self, node: ast.AST | None) -> Value:
        if node is None:
            return Value()
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return Value(set(FIND_PKG.findall(node.value)), [node.value])
        if isinstance(node, ast.Name):
            return self.env.get(node.id, Value())
        if isinstance(node, ast.Call):
            name = _call_name(node)
            if name in SHARE_CALLS:
                arg = node.args[0] if node.args else next((k.value for k in node.keywords if k.arg == "package"), None)
                inner = self.value(arg)
                return Value(set(inner.strings[:1]) | inner.packages, [])
            out = Value()
            for child in [*node.args, *(k.value for k in node.keywords)]:
                out = out | self.value(child)
            if isinstance(node.func, ast.Attribute):  # "x".join(...), Path(...).joinpath(...)
                out = out | self.value(node.func.value)
            return out
        out = Value()
        for child in ast.iter_child_nodes(node):
            out = out | self.value(child)
        return out

    def literal(self, node: ast.AST | None) -> str | None:
        """A package or executable name: a literal, or a variable holding exactly one literal."""
        v = self.value(node)
        if isinstance(node, (ast.Constant, ast.Name)) and len(v.strings) == 1 and not v.packages:
            s = v.strings[0]
            return s if re.fullmatch(r"[A-Za-z0-9_]+", s) else None
        return None

    def visit_Assign(self, node: ast.Assign) -> None:
        self.generic_visit(node)
        v = self.value(node.value)
        for target in node.targets:
            if isinstance(target, ast.Name):
                self.env[target.id] = v

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        self.generic_visit(node)
        if isinstance(node.target, ast.Name) and node.value is not None:
            self.env[node.target.id] = self.value(node.value)

    def visit_Import(self, node: ast.Import) -> None:
        if any(a.name == "xacro" for a in node.names):
            self.launch.commands.add("xacro")

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        if node.module == "xacro":
            self.launch.commands.add("xacro")

    def visit_Call(self, node: ast.Call) -> None:
        self.generic_visit(node)
        name = _call_name(node)
        kw = {k.arg: k.value for k in node.keywords if k.arg}
        if name in NODE_CALLS and "package" in kw:
            pkg = self.literal(kw["package"])
            if pkg:
                exe = self.literal(kw.get("executable") or kw.get("plugin") or kw.get("node_executable")) or "?"
                self.launch.nodes.add((pkg, exe))
        elif name in INCLUDE_CALLS:
            source = node.args[0] if node.args else kw.get("launch_description_source")
            self._include(self.value(source))
        elif name in PROCESS_CALLS:
            words = [w for s in self.value(node.args[0] if node.args else kw.get("cmd")).strings for w in s.split()]
            self._command(words)

    def _include(self, v: Value) -> None:
        files = [PurePosixPath(s).name for s in v.strings if LAUNCH_NAME.search(s)]
        for pkg in v.packages:
            self.launch.includes.add((pkg, files[-1] if files else "?"))

    def _command(self, words: list[str]) -> None:
        record_command(self.launch, words)


def record_command(launch: Launch, words: list[str]) -> None:
    words = [w.strip("'\"") for w in words if w.strip("'\"")]
    if not words:
        return
    head = PurePosixPath(words[0]).name
    if head == "ros2" and len(words) >= 4 and words[1] == "run":
        launch.nodes.add((words[2], words[3]))
    elif head == "ros2" and len(words) >= 4 and words[1] == "launch":
        launch.includes.add((words[2], PurePosixPath(words[3]).name))
    elif head in ("xacro", "gz", "ign", "ruby") or words[:2] == ["ign", "gazebo"]:
        if head == "xacro":
            launch.commands.add("xacro")
        elif head in ("gz", "ign") and len(words) > 1 and words[1] in ("sim", "gazebo"):
            launch.commands.add("gz")


def read_python_launch(launch: Launch, text: str) -> bool:
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return False
    PythonLaunchReader(launch).visit(tree)
    return True


def read_xml_launch(launch: Launch, text: str) -> bool:
    if "<launch" not in text or re.search(r"<node\b[^>]*\btype\s*=", text):  # a ROS 1 file: <node type=…>
        return False
    for tag, attrs in re.findall(r"<(node|include|executable|composable_node|node_container)\b([^>]*)>", text):
        a = {k: v1 or v2 for k, v1, v2 in ATTR.findall(attrs)}
        if tag in ("node", "composable_node", "node_container") and re.fullmatch(r"\w+", a.get("pkg", "")):
            launch.nodes.add((a["pkg"], a.get("exec") or a.get("plugin") or "?"))
        elif tag == "include":
            file = a.get("file", "")
            for pkg in FIND_PKG.findall(file):
                launch.includes.add((pkg, PurePosixPath(file).name))
        elif tag == "executable":
            record_command(launch, a.get("cmd", "").split())
    if "xacro" in text and "$(command" in text:
        launch.commands.add("xacro")
    return True


def read_yaml_launch(launch: Launch, text: str) -> bool:
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError:
        return False
    if not isinstance(doc, dict) or "launch" not in doc:
        return False

    def walk(x: object) -> None:
        if isinstance(x, dict):
            for key, v in x.items():
                if key in ("node", "composable_node", "node_container") and isinstance(v, dict):
                    pkg = str(v.get("pkg", ""))
                    if re.fullmatch(r"\w+", pkg):
                        launch.nodes.add((pkg, str(v.get("exec") or v.get("plugin") or "?")))
                elif key == "include" and isinstance(v, dict):
                    file = str(v.get("file", ""))
                    for pkg in FIND_PKG.findall(file):
                        launch.includes.add((pkg, PurePosixPath(file).name))
                elif key == "executable" and isinstance(v, dict):
                    record_command(launch, str(v.get("cmd", "")).split())
                walk(v)
        elif isinstance(x, list):
            for v in x:
                walk(v)

    walk(doc)
    return True


def is_launch_path(path: str) -> bool:
    parts = PurePosixPath(path).parts
    if any(p in ("test", "tests", "doc", "docs") for p in parts[:-1]):
        return False
    name = parts[-1]
    if re.search(r"\.launch(\.py|\.xml|\.yaml)?$", name) or re.search(r"_launch\.py$", name):
        return True
    return "launch" in parts[:-1] and name.endswith((".py", ".xml", ".yaml")) and name != "__init__.py"


# ------------------------------------------------------------------------------------------- a project


@dataclass
class Project:
    repo: str
    commit: str
    own: dict[str, str]  # package name → its folder
    launches: list[Launch]
    controllers: set[str]
    hardware: set[str]
    systems: set[str]


def own_package(path: str, own: dict[str, str]) -> str | None:
    best = None
    for name, folder in own.items():
        if (folder == "" or path.startswith(folder + "/")) and (best is None or len(folder) > len(own[best])):
            best = name
    return best


def survey(snapshot: Snapshot, system_kind) -> Project:
    paths = snapshot.paths()
    manifests = [p for p in paths if PurePosixPath(p).name == "package.xml"]
    launch_paths = [p for p in paths if is_launch_path(p)]
    yaml_paths = [p for p in paths if p.endswith((".yaml", ".yml")) and p not in launch_paths]
    desc_paths = [p for p in paths if p.endswith(DESCRIPTION_SUFFIXES)]
    texts = snapshot.read(manifests + launch_paths + yaml_paths + desc_paths)
    own: dict[str, str] = {}
    for p in manifests:
        m = re.search(r"<name>\s*([\w\-]+)\s*</name>", texts.get(p, ""))
        if m:
            own[m.group(1)] = str(PurePosixPath(p).parent).replace(".", "", 1) if p == "package.xml" else \
                str(PurePosixPath(p).parent)
    launches = []
    for p in launch_paths:
        text = texts.get(p)
        if text is None:
            continue
        launch = Launch(p, own_package(p, own))
        ok = (read_python_launch(launch, text) if p.endswith(".py") and "generate_launch_description" in text
              else read_xml_launch(launch, text) if p.endswith((".xml", ".launch"))
              else read_yaml_launch(launch, text) if p.endswith(".yaml") else False)
        if ok:
            launches.append(launch)
    controllers: set[str] = set()
    for p in yaml_paths:
        text = texts.get(p, "")
        if "ros__parameters" in text:
            controllers.update(t for t in CONTROLLER_TYPE.findall(text) if not t.startswith(("sensor_msgs", "std_")))
    hardware: set[str] = set()
    systems: set[str] = set()
    for p in desc_paths:
        text = texts.get(p, "")
        hardware.update(HW_PLUGIN.findall(text))
        for attrs in PLUGIN_TAG.findall(text):
            a = {k: v1 or v2 for k, v1, v2 in ATTR.findall(attrs)}
            filename = a.get("filename", "")
            if GZ_SYSTEM.search(filename):  # Gazebo (gz-sim / Ignition) systems, not Classic's or GUI plugins
                systems.add(system_kind(filename, a.get("name", "")))
    return Project(snapshot.repo, snapshot.commit, own, launches, controllers, hardware, systems)


def started(project: Project, launch: Launch, seen: set[str] | None = None) -> set[str]:
    """The packages other than the project's own that `launch` starts, following its own includes."""
    seen = seen if seen is not None else set()
    if launch.path in seen:
        return set()
    seen.add(launch.path)
    out = {pkg for pkg, _ in launch.nodes if pkg not in project.own} | launch.commands
    for pkg, file in launch.includes:
        if pkg not in project.own:
            out.add(pkg)
            continue
        for other in project.launches:
            if other.package == pkg and PurePosixPath(other.path).name == file:
                out |= started(project, other, seen)
    return out


# ------------------------------------------------------------------------------------ what diffctl provides


@dataclass
class Provided:
    packages: set[str]
    stand_ins: set[str]  # GUI tools diffctl stands in for (the launch goes on)
    controllers: set[str]
    hardware: set[str]
    systems: set[str]


def diffctl_provides() -> Provided:
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    from diffctl import demo_nodes
    from diffctl.control import plugin_registry
    from diffctl.sim import runner
    from diffctl.workspace import builtin, gui_tools, package_index

    packages = (package_index.component_packages() | set(builtin.replacement_packages())
                | set(demo_nodes.PACKAGES) | {pkg for pkg, _ in gui_tools.MAPPED})
    packages |= {"xacro", "gz"}  # the xacro and gz commands (pyproject's scripts and dependencies)
    stand_ins = {"rqt_gui", "rqt", "plotjuggler"}
    systems = set(runner.NATIVE_SYSTEMS) | set(runner.MODEL_SYSTEMS)
    return Provided(packages, stand_ins, set(plugin_registry.controller_types()),
                    set(plugin_registry.hardware_plugins()), systems)


def is_stand_in(pkg: str, provided: Provided) -> bool:
    return pkg in provided.stand_ins or pkg.startswith("rqt_")


# Why a package is not provided, where the reason is not "not yet": the stacks too big to provide faithfully here
# (a sourced ROS 2 runs the real ones), drivers of real hardware, Gazebo Classic (not Jazzy's Gazebo).
TOO_BIG = re.compile(r"^(nav2_\w+|opennav_\w+|slam_toolbox|cartographer_ros|moveit\w*|rmf_\w+)$")
HARDWARE = {
    "micro_ros_agent", "nmea_navsat_driver", "ld08_driver", "hls_lfcd_lds_driver", "rplidar_ros", "sllidar_ros2",
    "realsense2_camera", "usb_cam", "camera_ros", "ur_robot_driver", "ouster_ros", "velodyne_driver",
}
CLASSIC = {"gazebo_ros", "gazebo_ros2_control"}


def reason(pkg: str) -> str:
    if TOO_BIG.match(pkg):
        return "too big"
    if pkg in HARDWARE:
        return "hardware driver"
    return ""


# ------------------------------------------------------------------------------------------------ report


def load_list(path: Path) -> list[tuple[str, str, bool]]:
    """(repository, commit, whether it is a library: its packages are standard ones, not a robot's own)."""
    rows = []
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            repo, commit, *tags = line.split()
            rows.append((repo, commit, "library" in tags))
    return rows


def rank(counter: dict[str, set[str]], n_repos: int, is_provided, extra=None) -> list[dict]:
    rows = []
    for name, repos in sorted(counter.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        row = {"name": name, "repos": len(repos), "share": round(100 * len(repos) / n_repos),
               "provided": is_provided(name)}
        if extra:
            row.update(extra(name))
        rows.append(row)
    return rows


def report(projects: list[Project], robot_packages: set[str], provided: Provided) -> dict:
    """`robot_packages`: packages of the surveyed robots' own repositories; a launch of one robot that starts
    another's (turtlebot4_description from the TurtleBot 4 simulator) finds it in a workspace of the sources."""
    n = len(projects)
    pkg_repos: dict[str, set[str]] = defaultdict(set)
    pkg_launches: Counter[str] = Counter()
    ctl_repos: dict[str, set[str]] = defaultdict(set)
    hw_repos: dict[str, set[str]] = defaultdict(set)
    sys_repos: dict[str, set[str]] = defaultdict(set)
    outcome: Counter[str] = Counter()
    blockers: Counter[str] = Counter()  # the one missing package of launches missing exactly one
    per_repo = []
    for p in projects:
        ok_here = counted_here = 0
        for launch in p.launches:
            pkgs = started(p, launch) - robot_packages
            if pkgs & CLASSIC:
                outcome["gazebo classic (not counted)"] += 1
                continue
            counted_here += 1
            for pkg in pkgs:
                pkg_repos[pkg].add(p.repo)
                pkg_launches[pkg] += 1
            missing = {q for q in pkgs if q not in provided.packages and not is_stand_in(q, provided)}
            reasons = {reason(q) for q in missing}
            if not missing:
                outcome["stand-in" if any(is_stand_in(q, provided) for q in pkgs) else "provided"] += 1
                ok_here += 1
            elif "too big" in reasons:
                outcome["too big"] += 1
            elif "hardware driver" in reasons:
                outcome["hardware driver"] += 1
            else:
                outcome["not provided"] += 1
            if len(missing) == 1:
                blockers[next(iter(missing))] += 1
        for c in p.controllers:
            ctl_repos[c].add(p.repo)
        for h in p.hardware:
            hw_repos[h].add(p.repo)
        for s in p.systems:
            sys_repos[s].add(p.repo)
        per_repo.append({"repo": p.repo, "commit": p.commit, "launches": counted_here, "covered": ok_here})

    def package_provided(k: str) -> object:
        return "stand-in" if is_stand_in(k, provided) else True if k in provided.packages else reason(k) or False

    return {
        "repositories": n,
        "launches": sum(v for k, v in outcome.items() if "not counted" not in k),
        "outcome": dict(outcome),
        "packages": rank(pkg_repos, n, package_provided,
                         lambda k: {"launches": pkg_launches[k], "sole_blocker": blockers.get(k, 0)}),
        "controllers": rank(ctl_repos, n, lambda k: k in provided.controllers),
        "hardware": rank(hw_repos, n, lambda k: k in provided.hardware),
        "systems": rank(sys_repos, n, lambda k: k in provided.systems),
        "per_repo": per_repo,
    }


def mark(v: object) -> str:
    return {True: "yes", False: "**no**"}.get(v, f"no ({v})" if v != "stand-in" else "stand-in")  # type: ignore


def coverage_line(result: dict) -> str:
    o, total = result["outcome"], result["launches"]
    ok = o.get("provided", 0) + o.get("stand-in", 0)

    def pct(k: int) -> str:
        return f"{100 * k / max(total, 1):.0f} %"

    return (f"{result['repositories']} repositories, {total} launch files: {ok} ({pct(ok)}) start only packages "
            f"diffctl provides ({o.get('stand-in', 0)} of them with a GUI tool stood in for); the rest need Nav2, "
            f"SLAM, MoveIt or Open-RMF ({o.get('too big', 0)}, {pct(o.get('too big', 0))}), drivers of real "
            f"hardware ({o.get('hardware driver', 0)}, {pct(o.get('hardware driver', 0))}) or another package "
            f"({o.get('not provided', 0)}, {pct(o.get('not provided', 0))}); "
            f"{o.get('gazebo classic (not counted)', 0)} Gazebo Classic launch files are not counted")


def markdown(result: dict, top: int) -> str:
    lines = [coverage_line(result), ""]
    lines += ["| package | repositories | launch files | the one package missing in | diffctl |",
              "|---|---|---|---|---|"]
    for r in result["packages"][:top]:
        lines.append(f"| {r['name']} | {r['repos']} ({r['share']} %) | {r['launches']} | {r['sole_blocker']} | "
                     f"{mark(r['provided'])} |")
    for key, title in (("controllers", "controller type"), ("hardware", "ros2_control hardware"),
                       ("systems", "Gazebo system")):
        lines += ["", f"| {title} | repositories | diffctl |", "|---|---|---|"]
        lines += [f"| {r['name']} | {r['repos']} ({r['share']} %) | {mark(r['provided'])} |"
                  for r in result[key][:top]]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("snapshots", type=Path, help="folder of the repositories (owner+name/repo or owner+name)")
    parser.add_argument("--repos", type=Path, default=Path(__file__).with_name("package_survey_repos.tsv"))
    parser.add_argument("--json", type=Path, help="write the whole count here")
    parser.add_argument("--top", type=int, default=30)
    parser.add_argument("--launches", action="store_true", help="print each launch file and what it starts")
    parser.add_argument("--assume", default="", help="count these packages (comma-separated) as provided: what if")
    args = parser.parse_args(argv)
    provided = diffctl_provides()
    provided.packages |= {p for p in args.assume.split(",") if p}
    from diffctl.sim.plugins.system_names import system_kind

    projects: list[Project] = []
    robot_packages: set[str] = set()
    for repo, commit, library in load_list(args.repos):
        project = survey(Snapshot(repo, git_dir_of(args.snapshots, repo), commit), system_kind)
        projects.append(project)
        if not library:
            robot_packages |= set(project.own)
    if args.launches:
        for project in projects:
            for launch in project.launches:
                pkgs = started(project, launch) - robot_packages
                missing = sorted(q for q in pkgs if q not in provided.packages and not is_stand_in(q, provided))
                print(f"{project.repo}:{launch.path}: {' '.join(sorted(pkgs))}"
                      + (f"  MISSING {' '.join(missing)}" if missing else ""))
    result = report(projects, robot_packages, provided)
    if args.json:
        args.json.write_text(json.dumps(result, indent=1))
    print(markdown(result, args.top))
    return 0


if __name__ == "__main__":
    sys.exit(main())
