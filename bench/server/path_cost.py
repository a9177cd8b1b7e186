#!/usr/bin/env python3
"""User-space instructions per request of ncpostd, by part (valgrind --tool=callgrind): what the
machine's load cannot change, unlike req/s. The server runs under callgrind with one worker and
one IO thread; a keep-alive client sends N requests, and a run with one (the warm-up: caches,
first allocations) is subtracted, so start-up and shutdown cancel out.

    path_cost.py NCPOSTD [N]

Requests: GET /healthz; POST /v1/posts without a profile (400 from the worker: the server path
with no engine work); POST /v1/posts?profile=linuxcnc of a tiny program (34 canonical calls).
Parts: the server (ncpost::server, Asio/Beast, spdlog, JSON), the engine (other ncpost::),
libxml2/libxslt (the render stage's library), the allocator, the rest of libc/libstdc++.
"""
import http.client
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TINY = os.path.join(ROOT, "tests/golden/trace/cases/curves.stp")


def run(binary, path, body, n):
    work = tempfile.mkdtemp(prefix="path-cost-")
    log = os.path.join(work, "log")
    out = os.path.join(work, "callgrind.%p")
    with open(log, "w") as err:
        proc = subprocess.Popen(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                                 binary, "--listen", "127.0.0.1:0", "--workers", "1",
                                 "--io-threads", "1"], stderr=err, stdout=err)
    port = None
    for _ in range(600):
        time.sleep(0.1)
        m = re.search(r'"listening":"127\.0\.0\.1:(\d+)"', open(log).read())
        if m:
            port = int(m.group(1))
            break
    if port is None:
        proc.kill()
        sys.exit(f"{binary} did not start under valgrind")
    c = http.client.HTTPConnection("127.0.0.1", port)
    for _ in range(n):
        c.request("POST" if body else "GET", path, body=body)
        c.getresponse().read()
    c.close()
    proc.terminate()
    proc.wait(600)
    [name] = [f for f in os.listdir(work) if f.startswith("callgrind.")]
    text = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100",
                           os.path.join(work, name)], capture_output=True, text=True).stdout
    costs = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+(.*)", line)
        if m and "PROGRAM TOTALS" not in line:
            costs[m.group(2)] = costs.get(m.group(2), 0) + int(m.group(1).replace(",", ""))
    subprocess.run(["rm", "-rf", work])
    return costs


def part(symbol):
    if re.search(r"ncpost::server|boost::|spdlog|fmt::|nlohmann", symbol):
        return "server"
    if "ncpost::" in symbol:
        return "engine"
    if re.search(r"libxml|libxslt|xml|xslt|valuePush", symbol, re.I):
        return "libxml2/libxslt"
    if re.search(r"malloc|free|operator new|operator delete", symbol):
        return "allocator"
    return "libc/libstdc++"


def main():
    binary = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    tiny = open(TINY, "rb").read()
    for label, path, body in (("GET /healthz", "/healthz", None),
                              ("POST /v1/posts (400, no engine)", "/v1/posts", tiny),
                              ("POST /v1/posts?profile=linuxcnc, tiny", "/v1/posts?profile=linuxcnc", tiny)):
        base = run(binary, path, body, 1)
        full = run(binary, path, body, n)
        parts = {}
        for symbol in set(base) | set(full):
            p = part(symbol)
            parts[p] = parts.get(p, 0) + (full.get(symbol, 0) - base.get(symbol, 0)) / (n - 1)
        total = sum(parts.values())
        detail = ", ".join(f"{p} {v / 1e3:.1f}k" for p, v in sorted(parts.items(), key=lambda x: -x[1]))
        print(f"{label}: {total / 1e3:.1f}k instructions per request ({detail})", flush=True)


if __name__ == "__main__":
    main()
