"""What the browser tests of the operator page share: a free loopback port, headless chromium (Debian's
chromium-driver + python3-selenium), a cellctl process that dies with the test, waiting on a condition
with a time-out, and posting a command."""
import atexit
import ctypes
import json
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

PR_SET_PDEATHSIG = 1  # <sys/prctl.h>


class PageSession:
    def __init__(self, out):
        self.out = out
        os.makedirs(out, exist_ok=True)
        s = socket.socket()
        s.bind(("127.0.0.1", 0))
        self.port = s.getsockname()[1]
        s.close()
        self.base = f"http://127.0.0.1:{self.port}/"
        self.proc = None
        # The browser first: its start-up is the heavy part.
        options = webdriver.ChromeOptions()
        for a in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1200,900"):
            options.add_argument(a)
        self.driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
        self.driver.get("about:blank")

    def start(self, argv):
        """cellctl with `argv`, serving the page on this session's port; its output in OUT/cellctl.out."""
        log = open(os.path.join(self.out, "cellctl.out"), "w")
        self.proc = subprocess.Popen(argv + ["--http", f"127.0.0.1:{self.port}"], stdin=subprocess.DEVNULL,
                                     stdout=log, stderr=subprocess.STDOUT,
                                     preexec_fn=lambda: ctypes.CDLL("libc.so.6").prctl(PR_SET_PDEATHSIG,
                                                                                      signal.SIGTERM))
        # A failed assertion must not leave cellctl serving (a held virtual-time run never ends); the
        # kernel's parent-death signal covers this script being killed itself (a CTest time-out).
        atexit.register(lambda: self.proc.poll() is None and self.proc.kill())
        self.until(lambda: urllib.request.urlopen(self.base, timeout=2).status == 200, "the page to be served")

    def fail(self, msg):
        if self.proc:
            self.proc.kill()
        try:
            self.driver.quit()
        except Exception:
            pass
        print("FAIL:", msg, "— cellctl's output:", open(os.path.join(self.out, "cellctl.out")).read(), sep="\n")
        sys.exit(1)

    def until(self, cond, what, timeout=30):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                if cond():
                    return
            except Exception:
                pass
            if self.proc.poll() is not None:
                self.fail(f"cellctl ended ({self.proc.returncode}) while waiting for {what}")
            time.sleep(0.05)
        self.fail(f"timed out waiting for {what}")

    def log_in(self, token):
        """Logs the page in: the token typed into its login form, sent once; the form then hides."""
        from selenium.webdriver.common.by import By
        from selenium.webdriver.support import expected_conditions as EC
        from selenium.webdriver.support.ui import WebDriverWait
        wait = WebDriverWait(self.driver, 30)
        field = wait.until(EC.visibility_of_element_located((By.ID, "token")))
        field.send_keys(token)
        self.driver.find_element(By.ID, "log-in").click()
        wait.until(EC.invisibility_of_element_located((By.ID, "login")))
        assert self.driver.find_element(By.ID, "token").get_attribute("value") == "", "the page kept the token"

    def metrics(self, token):
        """/metrics, with the token as Prometheus sends it."""
        req = urllib.request.Request(self.base + "metrics", headers={"Authorization": "Bearer " + token})
        return urllib.request.urlopen(req, timeout=5).read().decode()

    def post(self, cmd, tok=None, body=None):
        data = json.dumps(body).encode() if body is not None else b""
        req = urllib.request.Request(self.base + "cmd/" + cmd, method="POST", data=data)
        if tok:
            req.add_header("X-Cellctl-Token", tok)
        try:
            with urllib.request.urlopen(req, timeout=10) as r:
                return r.status, json.loads(r.read())
        except urllib.error.HTTPError as e:
            return e.code, json.loads(e.read())
