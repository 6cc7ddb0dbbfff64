"""A stand-in node: writes its command line, the parameter files it was given (read back) and ROS_LOG_DIR as JSON
to the file $ECHO_TO, then exits 0."""

import json
import os
import sys

import yaml

argv = sys.argv[1:]
files = {}
for i, word in enumerate(argv[:-1]):
    if word == "--params-file":
        with open(argv[i + 1]) as f:
            files[argv[i + 1]] = yaml.safe_load(f)
with open(os.environ["ECHO_TO"], "w") as out:
    json.dump({"argv": argv, "params_files": files, "ros_log_dir": os.environ.get("ROS_LOG_DIR")}, out)
