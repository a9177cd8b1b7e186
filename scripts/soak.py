#!/usr/bin/env python3
"""Soak test of ncpostd (issue 23): mixed traffic for a while, then the error rate, latency
percentiles and resident memory sampled every 10 s, which must be flat after warm-up.

    scripts/soak.py [--minutes 30] [--clients 6] [--build build] [--corpus ../shared/corpus]

Starts its own ncpostd on 127.0.0.1 (an ephemeral port, a writable copy of the built-in
profiles, an admin token) and stops it at the end; sends nothing anywhere else. The traffic,
each client picking at random: small and large posts (the large ones read whole or dropped
after the first 64 KiB), inspections, P28 conversions, JSON traces, G-code translations, bad
inputs, profile PUTs, and clients that disconnect mid-upload. Every answer must have the status
its request expects; anything else is an error. Exit 1 when there is an error or when memory
grows after warm-up (the last third's highest sample more than 10% above the middle third's;
not judged with --smoke, the short run ctest makes so that the script keeps working).
docs/reliability.md ("Soak") has the figures of a run.
"""

import argparse
import http.client
import json
import os
import random
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOKEN = "soak-admin-token"


def start_server(build, profiles_dir, token_file):
    server = subprocess.Popen(
        [os.path.join(build, "bin", "ncpostd"), "--listen", "127.0.0.1:0", "--profiles",
         profiles_dir, "--admin-token-file", token_file, "--access-log", "off",
         "--job-timeout", "60"],
        stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    deadline = time.time() + 30
    while time.time() < deadline:
        line = server.stderr.readline()
        if not line:
            break
        try:
            record = json.loads(line)
        except ValueError:
            continue
        if "listening" in record:
            # Keep draining stderr so that the server never blocks on a full pipe.
            threading.Thread(target=lambda: [None for _ in server.stderr], daemon=True).start()
            return server, int(record["listening"].rsplit(":", 1)[1])
    server.kill()
    raise SystemExit("ncpostd did not say where it listens")


def resident_kib(pid):
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def multipart(parts):
    boundary = "soak" + "%016x" % random.getrandbits(64)
    body = b""
    for name, filename, data in parts:
        body += (f"--{boundary}\r\nContent-Disposition: form-data; name=\"{name}\"; "
                 f"filename=\"{filename}\"\r\nContent-Type: application/octet-stream\r\n\r\n"
                 ).encode() + data + b"\r\n"
    body += f"--{boundary}--\r\n".encode()
    return body, f"multipart/form-data; boundary={boundary}"


class Traffic:
    def __init__(self, port, files):
        self.port = port
        self.files = files
        self.lock = threading.Lock()
        self.latencies = {}  # kind -> [seconds]
        self.errors = []
        self.count = 0

    def record(self, kind, seconds, problem=None):
        with self.lock:
            self.count += 1
            self.latencies.setdefault(kind, []).append(seconds)
            if problem:
                self.errors.append(f"{kind}: {problem}")

    def request(self, kind, method, path, body, expect, headers=None, read_limit=None):
        started = time.monotonic()
        problem = None
        try:
            conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=120)
            conn.request(method, path, body=body, headers=headers or {})
            response = conn.getresponse()
            if read_limit is None:
                response.read()
            else:
                response.read(read_limit)  # then drop the connection mid-stream
            if response.status not in expect:
                problem = f"{method} {path}: status {response.status}, expected {expect}"
            conn.close()
        except (OSError, http.client.HTTPException) as error:
            problem = f"{method} {path}: {error!r}"
        self.record(kind, time.monotonic() - started, problem)

    def disconnect_mid_upload(self):
        started = time.monotonic()
        try:
            with socket.create_connection(("127.0.0.1", self.port), timeout=30) as s:
                body = self.files["large"]
                s.sendall(b"POST /v1/posts?profile=linuxcnc HTTP/1.1\r\nHost: soak\r\n"
                          b"Content-Type: application/p21\r\nContent-Length: " +
                          str(len(body)).encode() + b"\r\n\r\n" + body[:len(body) // 3])
        except OSError as error:
            self.record("disconnect-upload", time.monotonic() - started, repr(error))
            return
        self.record("disconnect-upload", time.monotonic() - started)

    def one(self, client):
        files = self.files
        p21 = {"Content-Type": "application/p21"}
        choice = random.random()
        if choice < 0.30:
            self.request("post-small", "POST", "/v1/posts?profile=linuxcnc", files["small"], {200},
                         p21)
        elif choice < 0.38:
            self.request("post-large", "POST", "/v1/posts?profile=linuxcnc", files["large"],
                         {200}, p21)
        elif choice < 0.43:
            self.request("post-large-dropped", "POST", "/v1/posts?profile=linuxcnc",
                         files["large"], {200}, p21, read_limit=64 * 1024)
        elif choice < 0.55:
            self.request("inspect", "POST", "/v1/inspections", files["small"], {200}, p21)
        elif choice < 0.63:
            self.request("convert-p28", "POST", "/v1/conversions?to=p28", files["small"], {200},
                         p21)
        elif choice < 0.71:
            self.request("trace-json", "POST", "/v1/traces?format=json", files["small"], {200},
                         p21)
        elif choice < 0.79:
            self.request("translate", "POST", "/v1/nc/translate?from=fanuc-0i&to=siemens-840d",
                         files["gcode"], {200}, {"Content-Type": "text/plain"})
        elif choice < 0.89:
            bad = random.choice([b"ISO-10303-21;\nHEADER;\n#1=;\n", b"\x00\xff" * 500,
                                 b"ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=PROJECT(#9);\n"])
            self.request("bad-input", "POST", "/v1/posts?profile=linuxcnc", bad, {400, 415, 422},
                         p21)
        elif choice < 0.94:
            body, content_type = multipart([("profile", "profile.json",
                                             files["profiles"][client % 3]),
                                            ("stylesheet", "post.xsl", files["stylesheet"])])
            self.request("profile-put", "PUT", f"/v1/profiles/soak-{client % 3}", body, {200, 201},
                         {"Content-Type": content_type, "Authorization": "Bearer " + TOKEN})
        else:
            self.disconnect_mid_upload()

    def run(self, client, until):
        random.seed(client * 7919 + int(time.time()))
        while time.monotonic() < until:
            self.one(client)


def percentile(values, q):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--minutes", type=float, default=30)
    parser.add_argument("--clients", type=int, default=6)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--large-mb", type=int, default=8)
    parser.add_argument("--smoke", action="store_true",
                        help="a short run (ctest): only the answers are judged, not the memory")
    args = parser.parse_args()

    work = tempfile.mkdtemp(prefix="ncpost-soak-")
    try:
        profiles = os.path.join(work, "profiles")
        shutil.copytree(os.path.join(ROOT, "stylesheets"), profiles)
        token_file = os.path.join(work, "token")
        with open(token_file, "w") as f:
            f.write(TOKEN)
        small = os.path.join(ROOT, "tests", "golden", "trace", "cases", "curves.stp")
        large = os.path.join(work, "large.stp")
        subprocess.run([os.path.join(args.build, "bin", "make_large_stepnc"), small,
                        str(args.large_mb), large], check=True, stdout=subprocess.DEVNULL)
        read = lambda path: open(path, "rb").read()
        profile = json.loads(read(os.path.join(ROOT, "stylesheets", "linuxcnc", "profile.json")))
        # The profile's id must be the one its PUT names: one body per id (soak-0 .. soak-2).
        profiles_by_id = []
        for i in range(3):
            profile["id"] = f"soak-{i}"
            profiles_by_id.append(json.dumps(profile).encode())
        files = {
            "profiles": profiles_by_id,
            "small": read(small),
            "large": read(large),
            "gcode": read(os.path.join(ROOT, "tests", "golden", "gcode", "fanuc-0i",
                                       "bolt-circle.nc")),
            "stylesheet": read(os.path.join(ROOT, "stylesheets", "linuxcnc", "post.xsl")),
        }
        server, port = start_server(args.build, profiles, token_file)
        try:
            traffic = Traffic(port, files)
            started = time.monotonic()
            until = started + args.minutes * 60
            threads = [threading.Thread(target=traffic.run, args=(c, until), daemon=True)
                       for c in range(args.clients)]
            for t in threads:
                t.start()
            samples = []
            while time.monotonic() < until:
                samples.append((round(time.monotonic() - started), resident_kib(server.pid)))
                print(f"{samples[-1][0]:6d} s  RSS {samples[-1][1] / 1024:7.1f} MiB  "
                      f"requests {traffic.count}  errors {len(traffic.errors)}", flush=True)
                time.sleep(min(10, max(0, until - time.monotonic())))
            for t in threads:
                t.join(timeout=180)
            samples.append((round(time.monotonic() - started), resident_kib(server.pid)))
        finally:
            server.terminate()
            server.wait(timeout=60)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    every = [s for values in traffic.latencies.values() for s in values]
    third = max(1, len(samples) // 3)
    middle = max(kib for _, kib in samples[third:2 * third] or samples)
    last = max(kib for _, kib in samples[2 * third:] or samples)
    growth = (last - middle) / middle if middle else 0
    summary = {
        "minutes": args.minutes,
        "clients": args.clients,
        "requests": traffic.count,
        "errors": len(traffic.errors),
        "error_rate": len(traffic.errors) / max(1, traffic.count),
        "p50_ms": round(1000 * percentile(every, 0.50), 1) if every else None,
        "p99_ms": round(1000 * percentile(every, 0.99), 1) if every else None,
        "by_kind": {kind: {"count": len(v), "p50_ms": round(1000 * percentile(v, 0.5), 1),
                           "p99_ms": round(1000 * percentile(v, 0.99), 1)}
                    for kind, v in sorted(traffic.latencies.items())},
        "rss_mib": {"first": round(samples[0][1] / 1024, 1),
                    "middle_third_max": round(middle / 1024, 1),
                    "last_third_max": round(last / 1024, 1), "growth": round(growth, 4)},
        "first_errors": traffic.errors[:10],
    }
    print(json.dumps(summary, indent=2))
    flat = args.smoke or growth <= 0.10
    if traffic.errors or not flat:
        print("soak FAILED: " + ("errors" if traffic.errors else "") +
              (" memory grows after warm-up" if not flat else ""), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
