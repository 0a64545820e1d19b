#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""attack_client.py: small loopback clients for test_serve_attack.sh and
bench_serve_attack.sh (issue 20).  Every socket has a timeout; every command
ends by itself within its stated bound.

  idle PORT N SECONDS        open N connections that send nothing; print
                             "open K" once they are open, hold them SECONDS
  events PORT N PAGE         open N /events streams (page id PAGE, or PAGE0..
                             if PAGE ends in '*'), print "200 A 503 B retry R"
                             (R: 503s with Retry-After) and whether a stream
                             opened just after closing them all answers 200
  race DIR PORT N OUTSIDE    flip DIR/race.scene between a link to
                             DIR/inside.scene and one to OUTSIDE while N
                             requests GET /scenes/race.scene; print how many
                             answers carried OUTSIDE's text ("leaked K of N")
  closed PORT N PATH         send N requests for PATH and close each at once
  idle_closed PORT SECONDS   open one connection that sends nothing; print
                             "closed after S s" when the server closes it, or
                             "open after SECONDS s"
  streams PORT N SECONDS     hold N /events streams (pages s0, s1, ...) SECONDS
  flood PORT K SECONDS PATH [HEADER]
                             K threads GET PATH back to back for SECONDS (one
                             extra request header, e.g. "Sec-Fetch-Site:
                             cross-site"); print how many were answered;
                             a '{}' in PATH becomes a number unique to the
                             request (e.g. a page id per request)
Every command connects from $ATTACK_SOURCE if it is set (e.g. 127.0.0.2).
"""
import os
import signal
import socket
import sys
import threading
import time


def connect(port, timeout=5.0):
    # ATTACK_SOURCE=127.0.0.2: connect from another loopback address (a
    # second client, as serve tells clients apart)
    src = os.environ.get("ATTACK_SOURCE")
    return socket.create_connection(("127.0.0.1", port), timeout=timeout,
                                    source_address=(src, 0) if src else None)


def request(port, path, timeout=10.0):
    """One GET; returns (status, headers text, body bytes)."""
    s = connect(port, timeout)
    try:
        s.sendall(f"GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n".encode())
        data = b""
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
    finally:
        s.close()
    head, _, body = data.partition(b"\r\n\r\n")
    status = int(head.split(b" ", 2)[1]) if head.startswith(b"HTTP/") else 0
    return status, head.decode("latin-1"), body


def status_line(s, deadline):
    """Reads a response head from s until the blank line or the deadline."""
    data = b""
    while b"\r\n\r\n" not in data and time.monotonic() < deadline:
        try:
            chunk = s.recv(4096)
        except socket.timeout:
            break
        if not chunk:
            break
        data += chunk
    head = data.partition(b"\r\n\r\n")[0].decode("latin-1")
    code = int(head.split(" ", 2)[1]) if head.startswith("HTTP/") else 0
    return code, head


def cmd_idle(port, n, seconds):
    socks = []
    for _ in range(n):
        try:
            socks.append(connect(port))
        except OSError:
            break
    print(f"open {len(socks)}", flush=True)
    time.sleep(seconds)
    for s in socks:
        s.close()


def open_stream(port, page):
    s = connect(port)
    s.sendall(f"GET /events?page={page} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
    return s, status_line(s, time.monotonic() + 5)


def cmd_events(port, n, page):
    socks, ok, busy, retry = [], 0, 0, 0
    for i in range(n):
        p = page[:-1] + str(i) if page.endswith("*") else page
        s, (code, head) = open_stream(port, p)
        socks.append(s)
        ok += code == 200
        busy += code == 503
        retry += code == 503 and "retry-after:" in head.lower()
    for s in socks:
        s.close()
    # a closed stream frees its slot at once (not at the next ping)
    deadline = time.monotonic() + 3
    again = 0
    while time.monotonic() < deadline:
        s, (code, _) = open_stream(port, page[:-1] + "x" if page.endswith("*") else page)
        s.close()
        if code == 200:
            again = 1
            break
        time.sleep(0.1)
    print(f"200 {ok} 503 {busy} retry {retry} reopen {again}", flush=True)


def cmd_race(d, port, n, outside):
    link = os.path.join(d, "race.scene")
    secret = open(outside, "rb").read()
    stop = threading.Event()

    def flip():
        i = 0
        while not stop.is_set():
            tmp = os.path.join(d, f".race{i % 2}")
            try:
                os.unlink(tmp)
            except FileNotFoundError:
                pass
            os.symlink("inside.scene" if i % 2 else outside, tmp)
            os.replace(tmp, link)
            i += 1

    t = threading.Thread(target=flip, daemon=True)
    t.start()
    leaked = 0
    try:
        for _ in range(n):
            _, _, body = request(port, "/scenes/race.scene")
            leaked += secret[:40] in body
    finally:
        stop.set()
        t.join(5)
    print(f"leaked {leaked} of {n}", flush=True)


def cmd_closed(port, n, path):
    for _ in range(n):
        s = connect(port)
        s.sendall(f"GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
        s.close()


def cmd_abandon(port, seconds, path):
    """Sends one request and closes the socket after `seconds`, unanswered."""
    s = connect(port)
    s.sendall(f"GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
    time.sleep(float(seconds))
    s.close()


def cmd_idle_closed(port, seconds):
    s = connect(port, timeout=seconds)
    t0 = time.monotonic()
    try:
        data = s.recv(1)
        print(f"closed after {time.monotonic() - t0:.1f} s" if not data else "data", flush=True)
    except socket.timeout:
        print(f"open after {seconds} s", flush=True)
    except OSError:
        print(f"closed after {time.monotonic() - t0:.1f} s", flush=True)
    s.close()


def cmd_streams(port, n, seconds):
    socks = []
    for i in range(n):
        try:
            socks.append(open_stream(port, f"s{i}")[0])
        except OSError:
            break
    print(f"open {len(socks)}", flush=True)
    time.sleep(seconds)
    for s in socks:
        s.close()


def cmd_flood(port, k, seconds, path, header=None):
    """Floods for `seconds`, or until SIGTERM: it then says how many requests
    were answered and exits at once (its sockets close unanswered)."""
    end = time.monotonic() + seconds
    done = [0] * k

    def stop(*_):
        print(f"answered {sum(done)} (stopped)", flush=True)
        os._exit(0)
    signal.signal(signal.SIGTERM, stop)

    def run(i):
        while time.monotonic() < end:
            try:
                s = connect(port, 10)
                extra = header + "\r\n" if header else ""
                p = path.replace("{}", f"{i}x{done[i]}")
                s.sendall(f"GET {p} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n{extra}Connection: close\r\n\r\n".encode())
                while s.recv(65536):
                    pass
                s.close()
                done[i] += 1
            except OSError:
                time.sleep(0.01)

    ts = [threading.Thread(target=run, args=(i,), daemon=True) for i in range(k)]
    for t in ts:
        t.start()
    for t in ts:
        t.join(seconds + 15)
    print(f"answered {sum(done)}", flush=True)


def main():
    a = sys.argv[1:]
    if not a:
        sys.exit(__doc__)
    if a[0] == "idle":
        cmd_idle(int(a[1]), int(a[2]), float(a[3]))
    elif a[0] == "events":
        cmd_events(int(a[1]), int(a[2]), a[3])
    elif a[0] == "race":
        cmd_race(a[1], int(a[2]), int(a[3]), a[4])
    elif a[0] == "closed":
        cmd_closed(int(a[1]), int(a[2]), a[3])
    elif a[0] == "abandon":
        cmd_abandon(int(a[1]), float(a[2]), a[3])
    elif a[0] == "idle_closed":
        cmd_idle_closed(int(a[1]), float(a[2]))
    elif a[0] == "streams":
        cmd_streams(int(a[1]), int(a[2]), float(a[3]))
    elif a[0] == "flood":
        cmd_flood(int(a[1]), int(a[2]), float(a[3]), a[4], a[5] if len(a) > 5 else None)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
