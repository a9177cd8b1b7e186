#!/usr/bin/env python3
"""Issue 24's figures: N concurrent posts of one large program against ncpostd with a memory
budget. Each client retries on 503 after its Retry-After until it gets its program (or the
deadline passes). Prints the server's peak resident memory (sampled from /proc every 10 ms),
the refusals, and the throughput of the admitted jobs.

usage: memory_budget.py NCPOSTD FILE CLIENTS [--max-inflight BYTES] [other ncpostd options]
"""
import re
import subprocess
import sys
import threading
import time


def main():
    ncpostd, path, clients = sys.argv[1], sys.argv[2], int(sys.argv[3])
    extra = sys.argv[4:]
    server = subprocess.Popen([ncpostd, "--listen", "127.0.0.1:0", "--access-log", "off"] + extra,
                              stderr=subprocess.PIPE, text=True)
    port = re.search(r"127\.0\.0\.1:(\d+)", server.stderr.readline()).group(1)
    url = f"http://127.0.0.1:{port}/v1/posts?profile=linuxcnc"

    def rss():
        with open(f"/proc/{server.pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS"):
                    return int(line.split()[1]) * 1024
        return 0

    peak, done = [0], [False]

    def sample():
        while not done[0]:
            peak[0] = max(peak[0], rss())
            time.sleep(0.01)

    sampler = threading.Thread(target=sample)
    sampler.start()
    base = rss()
    results = []
    lock = threading.Lock()

    def client():
        refusals = 0
        deadline = time.time() + 300
        while time.time() < deadline:
            out = subprocess.run(["curl", "-sS", "-o", "/dev/null", "-D", "-", "-w", "%{http_code}",
                                  "--data-binary", "@" + path, url],
                                 capture_output=True, text=True).stdout
            status = out[-3:]
            if status == "200":
                break
            refusals += 1
            retry = re.search(r"(?i)retry-after: (\d+)", out)
            time.sleep(int(retry.group(1)) if retry else 1)
        with lock:
            results.append((status, refusals))

    started = time.time()
    threads = [threading.Thread(target=client) for _ in range(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    wall = time.time() - started
    done[0] = True
    sampler.join()
    server.terminate()
    server.wait()
    size = __import__("os").path.getsize(path)
    ok = sum(1 for s, _ in results if s == "200")
    print(f"clients {clients}, file {size / 1e6:.0f} MB, options {' '.join(extra) or '(defaults)'}")
    print(f"  resident: {base >> 20} MiB at start, peak {peak[0] >> 20} MiB")
    print(f"  answered 200: {ok}/{clients}; 503 refusals before success: "
          f"{sum(r for _, r in results)}")
    print(f"  wall {wall:.1f} s; admitted throughput {ok * size / 1e6 / wall:.1f} MB/s, "
          f"{ok / wall:.2f} posts/s")


if __name__ == "__main__":
    main()
