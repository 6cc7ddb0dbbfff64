"""A process under test that ends by itself: prints its arguments, works a moment, exits 0."""

import sys
import time

print("Starting Up")
if sys.argv[1:]:
    print(f"Called with arguments {sys.argv[1:]}")
if "--exception" in sys.argv[1:]:
    raise Exception("Process had a pretend error")
print("Emulating Work")
time.sleep(0.3)
print("Done")
print("Shutting Down")
sys.exit(0)
