"""`python -m launch_testing.launch_test FILE` (diffctl/testing/launch_test.py)."""

from diffctl.testing.launch_test import main, run_and_exit

__all__ = ["main"]

if __name__ == "__main__":
    run_and_exit()
