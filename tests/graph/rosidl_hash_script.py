"""Run in a child interpreter with rosidl's Jazzy modules on sys.path: .msg/.srv/.action → .idl → RIHS01 hashes.

argv: a JSON file {"packages": {pkg: dir with msg/ srv/ action/}, "includes": {pkg: dir with msg/*.json}, "out": dir}.
Prints {type name: hash} for every type rosidl generated, as JSON on stdout's last line.
"""

import json
import sys
from pathlib import Path

from rosidl_adapter.action import convert_action_to_idl
from rosidl_adapter.msg import convert_msg_to_idl
from rosidl_adapter.srv import convert_srv_to_idl
from rosidl_generator_type_description import generate_type_hash


def main() -> None:
    spec = json.loads(Path(sys.argv[1]).read_text())
    out = Path(spec["out"])
    hashes: dict[str, str] = {}
    includes = dict(spec["includes"])
    # In name order, each package's descriptions an include of the next (robot_localization's services use
    # geographic_msgs, as a colcon build finds them in the installed share/ of the package built before).
    for pkg, src in sorted(spec["packages"].items()):
        src_dir = Path(src)
        idl_dir = out / "idl" / pkg
        tuples = []
        for kind, convert in (("msg", convert_msg_to_idl), ("srv", convert_srv_to_idl),
                              ("action", convert_action_to_idl)):
            for f in sorted((src_dir / kind).glob(f"*.{kind}")):
                convert(src_dir, pkg, Path(kind) / f.name, idl_dir / kind)
                tuples.append(f"{idl_dir}:{kind}/{f.stem}.idl")
        args = {"package_name": pkg, "output_dir": str(out / "json" / pkg), "idl_tuples": tuples,
                "include_paths": [f"{p}:{d}" for p, d in includes.items()]}
        args_file = out / f"{pkg}.args.json"
        args_file.write_text(json.dumps(args))
        for generated in generate_type_hash(str(args_file)):
            data = json.loads(Path(generated).read_text())
            for h in data["type_hashes"]:
                hashes[h["type_name"]] = h["hash_string"]
        includes[pkg] = str(out / "json" / pkg)
    print(json.dumps(hashes))


if __name__ == "__main__":
    main()
