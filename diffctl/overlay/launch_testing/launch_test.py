"""`python -m launch_testing.launch_test FILE` (diffctl/testing/launch_test.py)."""

import sys

from diffctl.testing.launch_test import main

if __name__ == "__main__":
    sys.exit(main())
