#!/usr/bin/python3
"""The web operator page in a real browser (Debian's chromium, headless, driven by chromium-driver and
python3-selenium) against `cellctl run --virtual-time --http`: a dry run on the emulators (over
simulated lines, so a loaded machine cannot stall them as it stalls pseudo-terminals — README, "Dry runs
on a loaded machine"), a recipe long enough in virtual time to be watched and commanded.

usage: operator_page_test.py CELLCTL CONFIG OUT_DIR

Runs the recipe with the page on a free loopback port and a token
file; checks that the page, logged in with the token (which it then no longer holds), shows the live
state (Execute, the step, the axes), that a command without the token is refused (401) and changes
nothing, that the Hold button (confirmation accepted) holds the cell by the page's session, that /metrics is Prometheus text with the loop's jitter histogram and
every device's exchanges and errors; saves a
screenshot (OUT_DIR/operator_page.png); then stops the run through the page (exit 130). Every wait is
on a condition with a time-out.
"""
import os
import re
import subprocess
import sys
import time

from selenium.webdriver.common.by import By
from selenium.webdriver.support import expected_conditions as EC
from selenium.webdriver.support.ui import WebDriverWait

from page_session import PageSession

cellctl, config, out = sys.argv[1:4]
os.makedirs(out, exist_ok=True)
token = "page-test-token-4711"
with open(os.path.join(out, "token"), "w") as f:
    f.write(token + "\n")
recipe = os.path.join(out, "slow.yaml")
with open(recipe, "w") as f:
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
  - name: slow move
    move: {to: {x: 40}, speed_mm_s: 2}
""")
page = PageSession(out)
driver, base, fail, post = page.driver, page.base, page.fail, page.post
page.start([cellctl, "-c", config, "run", recipe, "--virtual-time", "--journal", os.path.join(out, "run"),
            "--http-token-file", os.path.join(out, "token")])
proc = page.proc
try:
    driver.get(base)
    wait = WebDriverWait(driver, 30)
    page.log_in(token)
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Execute"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "label"), "long dwell"))
    wait.until(lambda d: len(d.find_elements(By.CSS_SELECTOR, "#axes tr")) == 2)
    assert driver.find_element(By.ID, "steps").text == "11", driver.find_element(By.ID, "steps").text

    # Without the token, or with a wrong one: 401, and the cell goes on.
    for tok in (None, "wrong"):
        code, body = post("hold", tok)
        assert code == 401 and body["ok"] is False, (code, body)
    time.sleep(0.5)  # long enough for a hold to show, were one taken (the page refreshes every 200 ms)
    assert driver.find_element(By.ID, "state").text == "Execute", driver.find_element(By.ID, "state").text

    # The Hold button, confirmation accepted: the cell holds (the page's session cookie, no token).
    driver.find_element(By.ID, "hold").click()
    wait.until(EC.alert_is_present()).accept()
    wait.until(EC.text_to_be_present_in_element((By.ID, "answer"), "hold: accepted"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Held"))
    driver.save_screenshot(os.path.join(out, "operator_page.png"))

    metrics = page.metrics(token)
    for needed in ('cellctl_loop_jitter_seconds_bucket{le="+Inf"}', "# TYPE cellctl_loop_jitter_seconds histogram",
                   'cellctl_device_link_fault{device="scu"} 0', "cellctl_runs_total 1",
                   "cellctl_web_commands_unauthorised_total 2"):
        assert needed in metrics, f"/metrics lacks {needed}:\n{metrics}"
    for device in ("scu", "spindle", "encoder"):
        exchanges = re.search(rf'^cellctl_device_exchanges_total{{device="{device}"}} (\d+)$', metrics, re.M)
        assert exchanges and int(exchanges.group(1)) > 0, f"/metrics counts no exchanges with the {device}:\n{metrics}"
        for kind in ("timeout", "bad_frame", "refused"):
            assert re.search(rf'^cellctl_device_errors_total{{device="{device}",kind="{kind}"}} \d+$', metrics, re.M), \
                f"/metrics lacks the {device}'s {kind} count:\n{metrics}"
finally:
    driver.quit()

code, body = post("stop", token)
assert code == 200 and body["ok"] is True, (code, body)
try:
    rc = proc.wait(timeout=60)
except subprocess.TimeoutExpired:
    fail("cellctl did not end after the stop")
if rc != 130:
    fail(f"exit {rc}, expected 130 (ended by the operator)")
print("operator page: live state, refused without token, hold by button, metrics, screenshot — passed")
