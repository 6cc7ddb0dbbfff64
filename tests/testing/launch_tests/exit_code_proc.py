"""A process under test that fails: exit code 1, or an exception with --exception."""

import sys

if "--exception" in sys.argv[1:]:
    raise Exception("Process had a pretend error")
print("Exiting with a code")
sys.exit(1)
