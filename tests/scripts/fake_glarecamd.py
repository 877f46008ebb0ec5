#!/usr/bin/env python3
"""A stand-in for glarecamd --simulate --count N, for scripts/soak's own test: writes N stacks
with results and logs as glarecamd does, and misbehaves as FAKE_FAULT says:
  fds     keeps a descriptor open per stack (a leak)
  rss     keeps 512 KiB per stack (a leak)
  lose    deletes a stack behind retention's back
  none    behaves
"""
import os
import sys
import time

args = sys.argv[1:]
out = args[args.index("--output") + 1]
count = int(args[args.index("--count") + 1])
fault = os.environ.get("FAKE_FAULT", "none")
print("info: glarecamd: ready: camera sim:fake", flush=True)
kept = []
for i in range(count):
    stack_id = f"20260621T{i:06d}Z-a40.00"
    os.makedirs(os.path.join(out, "stacks", stack_id))
    os.makedirs(os.path.join(out, "results", stack_id))
    open(os.path.join(out, "results", stack_id, "result.json"), "w").write("{}\n")
    print(f"info: glarecamd: wrote {out}/stacks/{stack_id}", flush=True)
    print(f"info: glarecamd: processed {stack_id}", flush=True)
    if fault == "fds":
        kept.append(open(os.path.join(out, "results", stack_id, "result.json")))
    elif fault == "rss":
        kept.append(bytearray(os.urandom(512 << 10)))
    elif fault == "lose" and i == count // 2:
        os.rmdir(os.path.join(out, "stacks", stack_id))
    time.sleep(0.02)
print(f"info: glarecamd: stopped after {count} stacks ({count} written, {count} processed, 0 failed)",
      flush=True)
