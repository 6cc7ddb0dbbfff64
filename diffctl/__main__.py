"""`python -m diffctl` runs the command line; the launcher starts components this way.

`run` is also the `diffctl` program's entry point: a `diffctl launch` starts its fork server before the
command line's modules are imported (diffctl/cli/launch_start.py), the rest goes to `diffctl.cli.main`.
"""

import sys


def run() -> None:
    if sys.argv[1:2] == ["launch"]:
        from diffctl.cli.launch_start import early_start

        early_start(sys.argv[1:])
    from diffctl.cli.main import main

    main()


if __name__ == "__main__":
    run()
