"""Exits with code 1 (launch_testing's exit_code_proc); --silent without a word, --exception by raising."""

import sys

if __name__ == "__main__":
    if "--silent" in sys.argv[1:]:
        sys.exit(1)
    if "--exception" in sys.argv[1:]:
        raise Exception("Process had a pretend error")
    print("Exiting with a code")
    sys.exit(1)
