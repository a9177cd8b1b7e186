#!/usr/bin/env python3
"""Time to first byte and total time of a large POST /v1/posts, for two ncpostd binaries side
by side in one run (docs/benchmarks.md, "HTTP service"): each is started on a free port, and
their runs alternate (before, after, before, ...) so that both see the same machine load.

    ttfb_compare.py BEFORE_NCPOSTD AFTER_NCPOSTD FILE PROFILE [FIRST_BYTE_RUNS] [TOTAL_RUNS]

FIRST_BYTE_RUNS (default 7) hang up after the first byte; TOTAL_RUNS (default 2) read the whole
program. Prints every run and the medians. Extra server options: NCPOSTD_ARGS.
"""
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ttfb import one_post  # noqa: E402


def start(binary):
    log = tempfile.NamedTemporaryFile(prefix="ncpostd-", suffix=".log", delete=False)
    args = [binary, "--listen", "127.0.0.1:0", "--access-log", "off"]
    args += os.environ.get("NCPOSTD_ARGS", "").split()
    proc = subprocess.Popen(args, stdout=log, stderr=log)
    for _ in range(200):
        time.sleep(0.05)
        m = re.search(r'"listening":"127\.0\.0\.1:(\d+)"', open(log.name).read())
        if m:
            return proc, int(m.group(1)), log.name
    proc.kill()
    sys.exit(f"{binary} did not start: {open(log.name).read()}")


def main():
    before_bin, after_bin, path, profile = sys.argv[1:5]
    first_runs = int(sys.argv[5]) if len(sys.argv) > 5 else 7
    total_runs = int(sys.argv[6]) if len(sys.argv) > 6 else 2
    body = open(path, "rb").read()
    servers = {"before": start(before_bin), "after": start(after_bin)}
    results = {name: {"first": [], "total": [], "upload": []} for name in servers}
    try:
        for kind, runs in (("first", first_runs), ("total", total_runs)):
            for i in range(runs):
                for name, (_, port, _) in servers.items():
                    r = one_post(port, body, profile, first_byte_only=(kind == "first"))
                    if r["status"] != "200":
                        sys.exit(f"{name}: status {r['status']}")
                    results[name]["first"].append(r["first_byte_s"])
                    results[name]["upload"].append(r["upload_s"])
                    if kind == "total":
                        results[name]["total"].append(r["total_s"])
                    print(f"{kind} run {i + 1} {name}: upload_s={r['upload_s']:.3f} "
                          f"first_byte_after_upload_s={r['first_byte_s']:.3f} "
                          + (f"total_after_upload_s={r['total_s']:.3f} " if kind == "total" else "")
                          + f"server_timing=\"{r['server_timing']}\"", flush=True)
    finally:
        for proc, _, log in servers.values():
            proc.terminate()
            proc.wait(30)
            os.unlink(log)
    print(f"# medians over {first_runs + total_runs} first-byte and {total_runs} total runs, "
          f"{len(body)} bytes, profile {profile}")
    for name, r in results.items():
        total = f"{statistics.median(r['total']):.3f}" if r["total"] else "-"
        print(f"{name}: upload_s={statistics.median(r['upload']):.3f} "
              f"first_byte_after_upload_s={statistics.median(r['first']):.3f} "
              f"total_after_upload_s={total}")


if __name__ == "__main__":
    main()
