#!/usr/bin/env python3
"""Time to first byte and total time of one large POST /v1/posts, measured from the moment the
upload finished (the last byte was handed to the kernel) rather than from the request's start,
which is what curl's time_starttransfer would mix in. Also reports the server's own account of
the time before the first byte (its Server-Timing header).

    ttfb.py PORT FILE PROFILE [RUNS] [--first-byte-only]

One line per run, then (with RUNS > 1) the medians. --first-byte-only hangs up once the first
byte of the program came (the server cancels the rest), for runs that measure only that.
"""
import re
import socket
import statistics
import sys
import time


def one_post(port, body, profile, first_byte_only=False):
    head = (f"POST /v1/posts?profile={profile} HTTP/1.1\r\nHost: 127.0.0.1\r\n"
            f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n").encode()
    s = socket.create_connection(("127.0.0.1", port))
    start = time.monotonic()
    s.sendall(head)
    s.sendall(body)
    uploaded = time.monotonic()
    received = b""
    first_body = None
    total = 0
    while True:
        data = s.recv(1 << 20)
        if not data:
            break
        total += len(data)
        if first_body is None:
            received += data
            end = received.find(b"\r\n\r\n")
            if end >= 0 and len(received) > end + 4:
                first_body = time.monotonic()
                if first_byte_only:
                    break
        elif len(received) < (1 << 16):
            received += data
    done = time.monotonic()
    s.close()
    header = received.split(b"\r\n\r\n", 1)[0].decode("latin-1")
    status = header.split(" ", 2)[1] if " " in header else "?"
    timing = re.search(r"(?im)^server-timing:\s*(.*)$", header)
    return {
        "status": status,
        "upload_s": uploaded - start,
        "first_byte_s": (first_body or done) - uploaded,
        "total_s": done - uploaded,
        "response_bytes": total,
        "server_timing": timing.group(1).strip() if timing else "",
    }


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    first_byte_only = "--first-byte-only" in sys.argv
    port, path, profile = int(args[0]), args[1], args[2]
    runs = int(args[3]) if len(args) > 3 else 1
    body = open(path, "rb").read()
    results = []
    for _ in range(runs):
        r = one_post(port, body, profile, first_byte_only)
        results.append(r)
        print(f"status={r['status']} upload_bytes={len(body)} upload_s={r['upload_s']:.3f} "
              f"first_byte_after_upload_s={r['first_byte_s']:.3f} "
              f"total_after_upload_s={r['total_s']:.3f} response_bytes={r['response_bytes']} "
              f"server_timing=\"{r['server_timing']}\"", flush=True)
    if runs > 1:
        med = lambda k: statistics.median(r[k] for r in results)
        print(f"median of {runs}: upload_s={med('upload_s'):.3f} "
              f"first_byte_after_upload_s={med('first_byte_s'):.3f} "
              f"total_after_upload_s={med('total_s'):.3f}")


if __name__ == "__main__":
    main()
