"""What the browser tests of the operator page share: a free loopback port, headless chromium (Debian's
chromium-driver + python3-selenium), a cellctl process that dies with the test, waiting on a condition
with a time-out, and posting a command."""
import atexit
import ctypes
import json
import os
import re
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

# A recipe that holds the cell in Execute for ten hours of dwell (on x alone): the job the page's
# commands act on while it runs.
SLOW_RECIPE = """recipe: {name: slow, version: "1", cell: demo-cell}
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
"""


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

    def text(self, element_id):
        from selenium.webdriver.common.by import By
        return self.driver.find_element(By.ID, element_id).text

    def screenshot(self, name, size=(1366, 768)):
        """The whole page at a window of `size` (the panel at the cell by default) into OUT/name.png."""
        self.driver.set_window_size(*size)
        # The page's own height, so that nothing below the fold is cut from the figure.
        height = self.driver.execute_script("return document.documentElement.scrollHeight")
        self.driver.set_window_size(size[0], max(size[1], height))
        self.driver.execute_script("window.scrollTo(0, 0)")
        self.driver.save_screenshot(os.path.join(self.out, name + ".png"))
        self.driver.set_window_size(*size)

    def click_confirmed(self, button, confirmation_part, answer_part, timeout=30):
        """Clicks `button`, checks and accepts its confirmation, waits for the answer."""
        from selenium.webdriver.common.by import By
        from selenium.webdriver.support import expected_conditions as EC
        from selenium.webdriver.support.ui import WebDriverWait
        wait = WebDriverWait(self.driver, timeout)
        element = self.driver.find_element(By.ID, button)
        assert element.is_enabled(), f"{button} is disabled: {element.get_attribute('title')}"
        element.click()
        alert = wait.until(EC.alert_is_present())
        assert confirmation_part in alert.text, alert.text
        alert.accept()
        try:
            wait.until(EC.text_to_be_present_in_element((By.ID, "answer"), answer_part))
        except Exception:
            raise AssertionError(f"{button}: the answer is {self.text('answer')!r}, not {answer_part!r}")

    def button_disabled_because(self, button, reason_part):
        """`button` is disabled and says why, beside it and in its tooltip (within the page's next live
        events: the state shown may be a refresh behind)."""
        from selenium.webdriver.common.by import By
        element = self.driver.find_element(By.ID, button)
        self.until(lambda: not element.is_enabled() and reason_part in self.text("why-" + button)
                   and reason_part in element.get_attribute("title"),
                   f"{button} disabled because {reason_part!r}", timeout=5)

    def check_trend(self, series):
        """The trend has its time axis (title and ticks), its position axis and a legend naming each
        of `series` with its unit (read at once: the page redraws the trend with every live event)."""
        texts = self.driver.execute_script(
            "const q = c => [...document.querySelectorAll('#trend ' + c)].map(e => e.textContent);"
            "return {titles: q('.x-title, .y-title'), x: q('.x-tick'), y: q('.y-tick'), legend: q('.legend-entry')};")
        assert texts["titles"] == ["run time (s)", "position (mm)"], texts
        assert len(texts["x"]) >= 2 and all(re.fullmatch(r"\d+(\.\d)?", t) for t in texts["x"]), texts
        assert texts["y"], texts
        assert texts["legend"] == [f"{s} (mm)" for s in series], texts

    def table(self, body_id):
        """The rows of a table body, each a list of its cells' texts, read at once (the page redraws its
        tables with every live event)."""
        return self.driver.execute_script(
            "return [...document.getElementById(arguments[0]).rows].map(r => [...r.cells].map(c => c.innerText))",
            body_id)

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
