"""A process under test: prints its arguments, counts until interrupted, then says goodbye."""

import sys
import time

if sys.argv[1:]:
    print(f"Called with arguments {sys.argv[1:]}")
print("Starting Up")
n = 0
try:
    while True:
        print(f"Loop {n}")
        n += 1
        time.sleep(0.2)
except KeyboardInterrupt:
    pass
print("Shutting Down")
sys.exit(0)
