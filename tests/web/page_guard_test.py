#!/usr/bin/python3
"""The operator page as a plant's IT security reviewer would probe it, against the real
`cellctl serve --virtual-time --http` (no browser: raw HTTP, so every header and every byte is the
test's own).

usage: page_guard_test.py CELLCTL CONFIG OUT_DIR

Checks, in order:
 - refused at start-up (exit 2): plain HTTP on a non-loopback address without --insecure-http, a token
   shorter than 16 bytes;
 - every response (the page, a 404, a 401) carries the security headers; wrong Host, wrong Origin: 403;
 - a command with no token, or with a wrong one of the right length: 401, nothing done;
 - a start whose client has gone before it is handled is not obeyed;
 - a 200 MB body without a token is answered 401 at once, unread: cellctl's VmHWM grows by less than
   32 MB; a 10 MB JSON and a 150 000-level one with the token: 413 at once; a deep one within the size
   limit: refused by the command path; a chunked body over 64 KiB: 413; a POST without a length: 411
   at once; cellctl alive throughout;
 - POST /login sets an HttpOnly, SameSite=Strict session cookie that /events and /cmd accept;
 - 16 live-event readers are served, the 17th is answered 503;
 - with a recipe running, 200 live-event readers connecting (16 served) and starts flooding in at
   about 1000/s, a stop posted with the page's session is answered, and the state leaves Execute,
   within 1 s;
 - after 5 wrong tokens an address is answered 429 (Retry-After) even with the right token, while the
   page's session still works; counted in /metrics;
 - HTTPS with a certificate the test makes (openssl req -x509), served on 0.0.0.0: the page, the
   Secure __Host- cookie; plain HTTP to it gets no page.
Every wait is on a condition with a time-out. Figures are printed (stop latency, memory).
"""
import http.client
import json
import os
import shutil
import signal
import socket
import ssl
import subprocess
import sys
import threading
import time

cellctl, config, out = sys.argv[1:4]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(os.path.join(out, "recipes"))
TOKEN = "guard-test-token-0123456789"
WRONG = "guard-test-token-9876543210"  # the right length, not the token
with open(os.path.join(out, "token"), "w") as f:
    f.write(TOKEN + "\n")
with open(os.path.join(out, "short-token"), "w") as f:
    f.write("short-token\n")
with open(os.path.join(out, "recipes", "slow.yaml"), "w") as f:
    f.write("""recipe: {name: slow, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 60}
steps:
  - name: long dwell
    repeat:
      times: 10
      steps:
        - {name: an hour, dwell: 3600}
""")

procs = []


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def serve(name, http_args, token_file="token"):
    log = open(os.path.join(out, name + ".out"), "w")
    p = subprocess.Popen([cellctl, "-c", config, "serve", "--virtual-time", "--runs", os.path.join(out, name, "runs"),
                          "--state-dir", os.path.join(out, name, "state"), "--recipes", os.path.join(out, "recipes"),
                          "--http-token-file", os.path.join(out, token_file)] + http_args,
                         stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT)
    procs.append(p)
    return p


def fail(msg):
    for p in procs:
        if p.poll() is None:
            p.kill()
    logs = "".join(f"--- {n}\n" + open(os.path.join(out, n)).read()[-3000:] for n in sorted(os.listdir(out))
                   if n.endswith(".out"))
    print("FAIL:", msg, "\n" + logs)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


def until(cond, what, timeout=30, proc=None):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            if cond():
                return
        except (OSError, http.client.HTTPException, ValueError):
            pass
        if proc is not None and proc.poll() is not None:
            fail(f"cellctl ended ({proc.returncode}) while waiting for {what}")
        time.sleep(0.05)
    fail(f"timed out waiting for {what}")


# --- refused at start-up ---------------------------------------------------------------------------
for name, args, token_file, needed in (
        ("plain-off-loopback", ["--http", f"0.0.0.0:{free_port()}"], "token", "--insecure-http"),
        ("short-token", ["--http", f"127.0.0.1:{free_port()}"], "short-token", "at least 16")):
    p = serve(name, args, token_file)
    try:
        rc = p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        fail(f"{name}: cellctl serve was not refused")
    text = open(os.path.join(out, name + ".out")).read()
    check(rc == 2 and needed in text, f"{name}: exit {rc}, expected 2 saying '{needed}':\n{text}")

# --- the page under test -------------------------------------------------------------------------------
PORT = free_port()
HOST = f"127.0.0.1:{PORT}"
proc = serve("page", ["--http", HOST])


def request(method, path, headers=None, body=None, host=HOST, timeout=10):
    c = http.client.HTTPConnection("127.0.0.1", PORT, timeout=timeout)
    try:
        c.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        c.putheader("Host", host)
        for k, v in (headers or {}).items():
            c.putheader(k, v)
        if body is not None:
            c.putheader("Content-Length", str(len(body)))
        c.endheaders(body)
        r = c.getresponse()
        return r.status, r.headers, r.read()
    finally:
        c.close()


def token(t=TOKEN):
    return {"X-Cellctl-Token": t}


def metrics():
    status, _, body = request("GET", "/metrics", {"Authorization": "Bearer " + TOKEN})
    check(status == 200, f"/metrics: {status}")
    values = {}
    for line in body.decode().splitlines():
        if line and not line.startswith("#"):
            key, value = line.rsplit(" ", 1)
            values[key] = float(value)
    return values


def state():
    return next(k.split('"')[1] for k in metrics() if k.startswith("cellctl_state{"))


def memory():
    fields = {}
    with open(f"/proc/{proc.pid}/status") as f:
        for line in f:
            if line.startswith(("VmRSS", "VmHWM")):
                fields[line.split(":")[0]] = int(line.split()[1]) // 1024
    return fields


until(lambda: request("GET", "/")[0] == 200, "the page to be served", proc=proc)

SECURITY = {"Content-Security-Policy": "default-src 'none'", "X-Frame-Options": "DENY", "Cache-Control": "no-store",
            "X-Content-Type-Options": "nosniff", "Referrer-Policy": "no-referrer"}
for method, path, headers in (("GET", "/", {}), ("GET", "/nothing-here", {}), ("POST", "/cmd/hold", {})):
    status, h, _ = request(method, path, headers, b"" if method == "POST" else None)
    for k, v in SECURITY.items():
        check(v in (h.get(k) or ""), f"{method} {path} ({status}): {k} is {h.get(k)!r}")
page_html = request("GET", "/")[2].decode()
check("<script>" not in page_html and "<style>" not in page_html and TOKEN not in page_html,
      "the page has inline code, or the token")

for host, origin, what in (("evil.example:%d" % PORT, None, "a foreign Host"), (f"127.0.0.1:{PORT + 1}", None, "another port"),
                           (HOST, "http://evil.example", "a foreign Origin"), (HOST, "null", "a null Origin")):
    status, _, _ = request("POST", "/cmd/hold", dict(token(), **({"Origin": origin} if origin else {})), b"", host=host)
    check(status == 403, f"{what}: {status}, expected 403")
status, _, _ = request("GET", "/", {"Origin": f"http://{HOST}"})
check(status == 200, f"the page's own Origin: {status}")

for headers, what in (({}, "no token"), (token(WRONG), "a wrong token of the right length")):
    status, _, body = request("POST", "/cmd/home", headers, b"{}")
    check(status == 401 and json.loads(body)["ok"] is False, f"{what}: {status} {body!r}")

# A start whose client has closed its connection by the time it is handled: not obeyed. The request is
# corked and the close (FIN) sent with it in one segment, so cellctl can read it only as a request
# whose client has gone.
s = socket.create_connection(("127.0.0.1", PORT))
s.setsockopt(socket.IPPROTO_TCP, socket.TCP_CORK, 1)
s.sendall(f"POST /cmd/home HTTP/1.1\r\nHost: {HOST}\r\nX-Cellctl-Token: {TOKEN}\r\nContent-Length: 2\r\n\r\n{{}}".encode())
s.shutdown(socket.SHUT_WR)
s.close()
until(lambda: metrics()["cellctl_web_commands_abandoned_total"] == 1, "the abandoned home to be counted", proc=proc)
check(metrics()["cellctl_runs_total"] == 0 and state() == "Idle", "a command whose client had gone was obeyed")


# --- bodies -----------------------------------------------------------------------------------------------
def big_body(path, headers, length, chunk=1 << 16):
    """Declares `length` bytes and sends them until the answer comes; (status line, bytes sent, seconds)."""
    s = socket.create_connection(("127.0.0.1", PORT))
    s.sendall((f"POST {path} HTTP/1.1\r\nHost: {HOST}\r\nContent-Type: application/json\r\n"
               + "".join(f"{k}: {v}\r\n" for k, v in headers.items())
               + f"Content-Length: {length}\r\n\r\n").encode())
    s.setblocking(False)
    block, sent, answer, t0 = b"[" * chunk, 0, b"", time.monotonic()
    while b"\r\n" not in answer and time.monotonic() - t0 < 10:
        try:
            answer += s.recv(4096)
            continue
        except BlockingIOError:
            pass
        except ConnectionResetError:
            break
        if sent < length:
            try:
                sent += s.send(block[:length - sent])
            except BlockingIOError:
                time.sleep(0.001)
            except (BrokenPipeError, ConnectionResetError):
                s.setblocking(True)
                s.settimeout(2)
                try:
                    answer += s.recv(4096)
                except OSError:
                    pass
                break
        else:
            time.sleep(0.001)
    s.close()
    return answer.split(b"\r\n")[0].decode(), sent, time.monotonic() - t0


before = memory()
line, sent, took = big_body("/cmd/start", {}, 200_000_000)
after = memory()
print(f"200 MB body without a token: '{line}' after {took * 1000:.0f} ms, {sent / 1e6:.1f} MB sent; "
      f"VmRSS {before['VmRSS']} -> {after['VmRSS']} MB, VmHWM {before['VmHWM']} -> {after['VmHWM']} MB")
check(" 401 " in line and took < 2, f"200 MB body without a token: '{line}' after {took:.1f} s")
check(after["VmHWM"] - before["VmHWM"] < 32, f"memory grew: {before} -> {after}")
for what, length in (("a 10 MB JSON", 10_000_000), ("a 150 000-level JSON", 150_000)):
    line, sent, took = big_body("/cmd/start", token(), length)
    check(" 413 " in line and took < 2, f"{what}: '{line}' after {took:.1f} s")
status, _, body = request("POST", "/cmd/start", token(), b"[" * 60_000)
check(json.loads(body)["ok"] is False, f"a 60 000-level JSON within 64 KiB: {status} {body!r}")
c = http.client.HTTPConnection("127.0.0.1", PORT, timeout=10)
c.putrequest("POST", "/cmd/hold", skip_host=True)
c.putheader("Host", HOST)
c.putheader("X-Cellctl-Token", TOKEN)
c.putheader("Transfer-Encoding", "chunked")
c.endheaders()
try:
    for _ in range(80):
        c.send(b"400\r\n" + b" " * 1024 + b"\r\n")
    c.send(b"0\r\n\r\n")
except OSError:
    pass
status = c.getresponse().status
c.close()
check(status == 413, f"a chunked body over 64 KiB: {status}")
# A POST without a length would be read until its client closes (httplib): refused at once instead.
t0 = time.monotonic()
s = socket.create_connection(("127.0.0.1", PORT), timeout=5)
s.sendall(f"POST /cmd/hold HTTP/1.1\r\nHost: {HOST}\r\nX-Cellctl-Token: {TOKEN}\r\n\r\n".encode())
line = s.recv(4096).split(b"\r\n")[0].decode()
s.close()
check(" 411 " in line and time.monotonic() - t0 < 1, f"a POST without Content-Length: '{line}'")
check(proc.poll() is None and state() == "Idle", "cellctl did not survive the bodies")

# --- the session -------------------------------------------------------------------------------------------
status, h, body = request("POST", "/login", token(), b"")
cookie = h.get("Set-Cookie") or ""
check(status == 200 and "HttpOnly" in cookie and "SameSite=Strict" in cookie and TOKEN not in cookie,
      f"login: {status} {cookie!r}")
SESSION = {"Cookie": cookie.split(";")[0]}
# Admitted by the session and judged by the cell: a hold in Idle is refused by the state (409), not 401.
status, _, body = request("POST", "/cmd/hold", SESSION, b"{}")
check(status == 409 and "is not possible in state Idle" in json.loads(body)["reason"],
      f"a command by the session: {status} {body!r}")
check(request("GET", "/events", {"Cookie": "cellctl_session=" + "0" * 32}, timeout=3)[0] == 401,
      "/events with a made-up session")


class Reader:
    """A live-event reader: its status line, then the state of each status event it is sent."""

    def __init__(self, headers):
        self.status, self.left_execute, self.states = None, None, []
        self.sock = socket.create_connection(("127.0.0.1", PORT), timeout=30)
        self.sock.sendall((f"GET /events HTTP/1.1\r\nHost: {HOST}\r\n"
                           + "".join(f"{k}: {v}\r\n" for k, v in headers.items()) + "\r\n").encode())
        self.thread = threading.Thread(target=self.read, daemon=True)
        self.thread.start()

    def read(self):
        buf = b""
        try:
            while True:
                data = self.sock.recv(65536)
                if not data:
                    return
                buf += data
                if self.status is None and b"\r\n" in buf:
                    self.status = int(buf.split(b" ")[1])
                while b"\n\n" in buf:
                    event, buf = buf.split(b"\n\n", 1)
                    if b"event: status" in event:
                        s = json.loads(event.split(b"data: ", 1)[1].split(b"\r\n")[0])["state"]
                        self.states.append(s)
                        if s != "Execute" and "Execute" in self.states and self.left_execute is None:
                            self.left_execute = time.monotonic()
        except OSError:
            return

    def close(self):
        try:
            self.sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        self.sock.close()


readers = [Reader(SESSION if i % 2 else token()) for i in range(17)]
until(lambda: all(r.status for r in readers), "17 readers answered")
codes = sorted(r.status for r in readers)
check(codes == [200] * 16 + [503], f"17 readers: {codes}")
for r in readers:
    r.close()
until(lambda: metrics()["cellctl_web_streams"] == 0, "the streams to be closed", proc=proc)

# --- a stop under a flood ------------------------------------------------------------------------------
status, _, body = request("POST", "/cmd/start", token(), json.dumps({"recipe": "slow"}).encode())
check(status == 200 and json.loads(body)["ok"], f"start: {status} {body!r}")
until(lambda: state() == "Execute", "the recipe to execute", proc=proc)

readers = [Reader(token()) for _ in range(200)]
until(lambda: all(r.status for r in readers), "200 readers answered", timeout=60)
live = [r for r in readers if r.status == 200]
check(len(live) == 16, f"{len(live)} of 200 readers served, expected 16")
until(lambda: all(r.states for r in live), "the live readers' first status")

START_BODY = b'{"recipe":"slow"}'
START = (f"POST /cmd/start HTTP/1.1\r\nHost: {HOST}\r\nX-Cellctl-Token: {TOKEN}\r\nContent-Type: application/json\r\n"
         f"Content-Length: {len(START_BODY)}\r\n\r\n").encode() + START_BODY
flooding, flood_sent = True, [0] * 8


def flood(i, rate=125):
    """One of 8 senders of starts, 125/s each: a new connection each, its answer read."""
    t0 = time.monotonic()
    while flooding:
        try:
            s = socket.create_connection(("127.0.0.1", PORT), timeout=5)
            s.sendall(START)
            s.recv(4096)
            s.close()
            flood_sent[i] += 1
        except OSError:
            pass
        delay = t0 + flood_sent[i] / rate - time.monotonic()
        if delay > 0:
            time.sleep(delay)


floods = [threading.Thread(target=flood, args=(i,), daemon=True) for i in range(8)]
flood_t0 = time.monotonic()
for t in floods:
    t.start()
time.sleep(1.5)  # the flood running for a while: not a wait for a condition, the load's duration
stop_t0 = time.monotonic()
status, _, body = request("POST", "/cmd/stop", SESSION, b"{}")
answered = time.monotonic() - stop_t0
until(lambda: any(r.left_execute for r in live), "the state to leave Execute", timeout=10)
left = min(r.left_execute for r in live if r.left_execute) - stop_t0
time.sleep(1.5)
flooding = False
for t in floods:
    t.join(timeout=10)
flood_rate = sum(flood_sent) / (time.monotonic() - flood_t0)
for r in readers:
    r.close()
print(f"stop under 200 readers and {flood_rate:.0f} starts/s: answered in {answered * 1000:.0f} ms "
      f"({json.loads(body).get('outcome') or json.loads(body).get('reason')}), state left Execute after "
      f"{left * 1000:.0f} ms")
check(status == 200 and json.loads(body)["ok"], f"stop: {status} {body!r}")
check(answered < 1 and left < 1, f"stop answered after {answered:.2f} s, state left Execute after {left:.2f} s")
check(flood_rate > 300, f"the flood reached only {flood_rate:.0f} starts/s")
until(lambda: metrics()["cellctl_web_streams"] == 0, "the streams to be closed", proc=proc)

# --- wrong tokens back off ----------------------------------------------------------------------------------
until(lambda: state() == "Stopped", "the stop to end", proc=proc)
for _ in range(6):
    status, _, _ = request("POST", "/cmd/reset", token(WRONG), b"{}")
status, h, _ = request("POST", "/cmd/reset", token(), b"{}")
check(status == 429 and int(h.get("Retry-After", "0")) >= 1, f"after 6 wrong tokens, the right one: {status}")
status, _, body = request("POST", "/cmd/reset", SESSION, b"{}")
check(status == 200 and json.loads(body)["ok"], f"the session while the address is held back: {status} {body!r}")
status, _, body = request("GET", "/metrics", SESSION)  # the token is held back here: the session
text = body.decode()
check('cellctl_web_requests_refused_total{why="throttled"} ' in text and
      'cellctl_web_requests_refused_total{why="throttled"} 0' not in text, f"/metrics: {text}")

# --- HTTPS ----------------------------------------------------------------------------------------------------
cert, key = os.path.join(out, "cert.pem"), os.path.join(out, "key.pem")
subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", key, "-out", cert, "-days", "1",
                "-subj", "/CN=localhost", "-addext", "subjectAltName=IP:127.0.0.1,DNS:localhost"],
               check=True, capture_output=True)
TLS_PORT = free_port()
tls_proc = serve("tls", ["--http", f"0.0.0.0:{TLS_PORT}", "--http-cert", cert, "--http-key", key])
context = ssl.create_default_context(cafile=cert)


def tls_request(method, path, headers=None):
    c = http.client.HTTPSConnection("127.0.0.1", TLS_PORT, context=context, timeout=10)
    try:
        c.request(method, path, body=b"" if method == "POST" else None, headers=headers or {})
        r = c.getresponse()
        return r.status, r.headers, r.read()
    finally:
        c.close()


until(lambda: tls_request("GET", "/")[0] == 200, "the page over HTTPS", proc=tls_proc)
status, h, _ = tls_request("POST", "/login", token())
cookie = h.get("Set-Cookie") or ""
check(status == 200 and cookie.startswith("__Host-") and "Secure" in cookie, f"HTTPS login: {status} {cookie!r}")
status, _, body = tls_request("POST", "/cmd/reset", {"Cookie": cookie.split(";")[0]})
# Judged by the cell (a reset in Idle: 409), not taken for a command whose client has gone (410).
check(status == 409 and "is not possible in state Idle" in json.loads(body)["reason"],
      f"a command over HTTPS by its session: {status} {body!r}")
try:
    plain = http.client.HTTPConnection("127.0.0.1", TLS_PORT, timeout=5)
    plain.request("GET", "/")
    plain_status = plain.getresponse().status
except (OSError, http.client.HTTPException):
    plain_status = None
check(plain_status != 200, "plain HTTP got the page from the HTTPS port")

for p in (proc, tls_proc):
    p.send_signal(signal.SIGTERM)
    try:
        rc = p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        fail("cellctl serve did not end after SIGTERM")
    check(rc == 0, f"cellctl serve: exit {rc} after SIGTERM")
print("page guard: start-up refusals, headers, Host/Origin, tokens, bodies, session, stream cap, stop under flood, "
      "back-off, HTTPS — passed")
