"""Counts once a second until interrupted (launch_testing's good_proc: 'Starting Up', 'Loop N', 'Shutting Down')."""

import sys
import time

if __name__ == "__main__":
    if sys.argv[1:]:
        print(f"Called with arguments {sys.argv[1:]}")
    print("Starting Up")
    n = 0
    try:
        while True:
            print(f"Loop {n}")
            n += 1
            time.sleep(1.0)
    except KeyboardInterrupt:
        pass
    print("Shutting Down")
    sys.exit(0)
