#!/usr/bin/env python3
"""Time to first byte and total time of one large POST /v1/posts, measured from the moment the
upload finished (the last byte was handed to the kernel) rather than from the request's start,
which is what curl's time_starttransfer would mix in.

    ttfb.py PORT FILE PROFILE
"""
import socket
import sys
import time

port, path, profile = int(sys.argv[1]), sys.argv[2], sys.argv[3]
body = open(path, "rb").read()
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
done = time.monotonic()
print(f"upload_bytes={len(body)} upload_s={uploaded - start:.3f} "
      f"first_byte_after_upload_s={(first_body or done) - uploaded:.3f} "
      f"total_after_upload_s={done - uploaded:.3f} response_bytes={total}")
