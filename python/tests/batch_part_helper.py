"""A part's process for the batch tests only (run_batch(part_command=...)): the part with id `crash` kills its own
process with SIGSEGV, as a crash in native code would, and `hang` sleeps past any timeout; others run as usual.
Not reachable from a manifest: only a Python caller of run_batch chooses the part's command."""

import json
import os
import signal
import sys
import time

from conform import batch

spec = json.load(sys.stdin)
if spec["id"] == "crash":
    os.kill(os.getpid(), signal.SIGSEGV)
if spec["id"] == "hang":
    time.sleep(600)
row = batch.run_part(spec)
print(batch._RESULT + json.dumps(row), flush=True)
