"""A stand-in process for launch tests: records that it ran, may print, sleep, ignore signals, exit with a code.

    step.py RECORD NAME [--print TEXT] [--sleep S] [--exit N] [--ignore-signals]

RECORD is a file the process appends NAME to when it starts ("-" for none), and NAME:printed once it has
printed TEXT.
"""

import argparse
import signal
import sys
import time

parser = argparse.ArgumentParser()
parser.add_argument("record")
parser.add_argument("name")
parser.add_argument("--print", dest="text")
parser.add_argument("--sleep", type=float, default=0.0)
parser.add_argument("--exit", type=int, default=0)
parser.add_argument("--ignore-signals", action="store_true")
args = parser.parse_args()
if args.ignore_signals:
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, signal.SIG_IGN)
if args.record != "-":
    with open(args.record, "a") as f:
        f.write(args.name + "\n")
if args.text:
    print(args.text, flush=True)
    if args.record != "-":
        with open(args.record, "a") as f:
            f.write(args.name + ":printed\n")
try:
    time.sleep(args.sleep)
except KeyboardInterrupt:
    sys.exit(130)  # stopped by the launcher, like a ROS node on Ctrl-C
sys.exit(args.exit)
