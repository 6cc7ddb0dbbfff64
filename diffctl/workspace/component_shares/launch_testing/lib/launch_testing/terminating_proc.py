"""Starts, works two seconds and ends by itself (launch_testing's terminating_proc); --exception fails."""

import sys
import time

if __name__ == "__main__":
    print("Starting Up")
    time.sleep(1.0)
    print("Ready")
    if sys.argv[1:]:
        print(f"Called with arguments {sys.argv[1:]}")
    if "--exception" in sys.argv[1:]:
        raise Exception("Process had a pretend error")
    try:
        print("Emulating Work")
        time.sleep(1.0)
        print("Done")
    except KeyboardInterrupt:
        pass
    print("Shutting Down")
    sys.exit(0)
