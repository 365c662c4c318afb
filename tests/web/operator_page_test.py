#!/usr/bin/python3
"""The web operator page in a real browser (Debian's chromium, headless, driven by chromium-driver and
python3-selenium) against `cellctl run --virtual-time --http`: a dry run on the emulators (over
simulated lines, so a loaded machine cannot stall them as it stalls pseudo-terminals — README, "Dry runs
on a loaded machine"), a recipe long enough in virtual time to be watched and commanded.

usage: operator_page_test.py CELLCTL CONFIG OUT_DIR

Runs the recipe with the page on a free loopback port and a token file, on a copy of CONFIG whose
faults hold the cell (stops: fault: 2), with a rehearsed spindle fault 1 s into the run. Checks, each
wait on a condition with a time-out:
 - the login: the token typed once and sent with Enter (the keyboard), then no longer in the page;
 - the fault: Held, each active fault with its remedy, and nothing under holds and commands;
   the buttons as PackML allows in Held (Hold disabled with its reason, Start with `cellctl serve`'s);
   figure OUT_DIR/fault.png; Reset (as often as the converter's own latch needs), then Unhold (each
   confirmed) bring the cell back to Execute;
 - Execute: the axes table names target, SCU and encoder positions and both homed facts for x and z;
   every device of the cell with its link up and a round trip; the trend with its time axis, position
   axis and a legend naming each line; every command button reachable by Tab; figures OUT_DIR/execute.png
   at 1366×768 and OUT_DIR/execute-tablet.png at 820×1180;
 - a command without the token, or with a wrong one, is refused (401) and changes nothing;
 - the Hold button holds the cell by the page's session: the hold is listed under holds and commands,
   not as a fault; figure OUT_DIR/held.png;
 - /metrics is Prometheus text with the loop's jitter histogram and every device's exchanges and errors;
 - the Stop button ends the run, the journal naming the page's session as the stop's source.
"""
import os
import re
import subprocess
import sys
import time

from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support import expected_conditions as EC
from selenium.webdriver.support.ui import WebDriverWait

from page_session import SLOW_RECIPE, PageSession

cellctl, config_given, out = sys.argv[1:4]
os.makedirs(out, exist_ok=True)
token = "page-test-token-4711"
with open(os.path.join(out, "token"), "w") as f:
    f.write(token + "\n")
config = os.path.join(out, "cell-faults-hold.yaml")
with open(config_given) as f:
    cell_text = f.read()
assert re.search(r"(?m)^  fault: 1$", cell_text), "the cell config's stops: fault: 1 was not found"
with open(config, "w") as f:
    f.write(re.sub(r"(?m)^  fault: 1$", "  fault: 2", cell_text))
recipe = os.path.join(out, "slow.yaml")
with open(recipe, "w") as f:
    f.write(SLOW_RECIPE + """  - name: slow move
    move: {to: {x: 40}, speed_mm_s: 2}
""")
page = PageSession(out)
driver, base, fail, post, text = page.driver, page.base, page.fail, page.post, page.text
page.start([cellctl, "-c", config, "run", recipe, "--virtual-time", "--journal", os.path.join(out, "run"),
            "--fault", "spindle:error@1+1", "--http-token-file", os.path.join(out, "token")])
proc = page.proc
try:
    driver.get(base)
    wait = WebDriverWait(driver, 30)
    # The login by keyboard: the field has the focus, Enter sends the form.
    wait.until(EC.visibility_of_element_located((By.ID, "token")))
    assert driver.switch_to.active_element.get_attribute("id") == "token", "the token field has no focus"
    driver.switch_to.active_element.send_keys(token + Keys.ENTER)
    wait.until(EC.invisibility_of_element_located((By.ID, "login")))
    assert driver.find_element(By.ID, "token").get_attribute("value") == "", "the page kept the token"
    assert token not in driver.page_source, "the token is in the page"

    # The rehearsed fault held the cell: the faults with their remedies, apart from holds and commands.
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Held"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "faults"), "spindle_temperature"))
    faults = text("faults")
    assert "Remedy: Motor over-temperature: let the spindle cool down" in faults, faults
    assert text("stops") == "none", text("stops")
    page.button_disabled_because("hold", "hold is taken only in Execute")
    page.button_disabled_because("clear", "clear is taken only in Aborted")
    page.button_disabled_because("start", "jobs start under cellctl serve")
    assert driver.find_element(By.ID, "unhold").is_enabled()
    page.screenshot("fault")
    # A reset clears the latches whose cause is gone and resets the converter, whose own fault then
    # goes: a second reset clears the rest (the journal says why the first could not).
    for _ in range(3):
        page.click_confirmed("reset", "reset the cell?", "reset: ")
        try:
            WebDriverWait(driver, 5).until(EC.text_to_be_present_in_element((By.ID, "faults"), "none"))
            break
        except Exception:
            pass
    assert text("faults") == "none", text("faults")
    page.click_confirmed("unhold", "unhold the cell?", "unhold: unholding")
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Execute"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "label"), "long dwell"))
    assert text("steps") == "11", text("steps")

    # Execute: the axes and devices named as such, the trend with its axes and legend.
    headers = [th.text for th in driver.find_elements(By.CSS_SELECTOR, "section[aria-label=axes] th")]
    assert headers == ["axis", "target (mm)", "SCU position (mm)", "encoder position (mm)", "homed: record",
                       "homed: SCU bit"], headers
    page.until(lambda: [r[0] for r in page.table("axes")] == ["x", "z"], "the axes x and z")
    page.until(lambda: re.fullmatch(r"-?\d+\.\d{3}", page.table("axes")[0][3]), "x's encoder position")
    assert page.table("axes")[1][3] == "—", "z has no encoder, yet the page shows it a position"
    devices = page.table("devices")
    assert [d[0] for d in devices] == ["scu", "spindle", "encoder"], devices
    for d in devices:
        assert d[1] == "up" and float(d[2]) > 0 and int(d[4]) > 0, d
    page.until(lambda: len(driver.find_elements(By.CSS_SELECTOR, "#trend .legend-entry")) == 3, "the legend")
    page.check_trend(["x SCU", "x encoder", "z SCU"])
    # Every command button is reached by Tab (and worked by Enter, as any button).
    reached = set()
    body = driver.find_element(By.TAG_NAME, "body")
    body.click()
    for _ in range(60):
        body.send_keys(Keys.TAB) if not reached else driver.switch_to.active_element.send_keys(Keys.TAB)
        reached.add(driver.switch_to.active_element.get_attribute("id"))
    missing = {"hold", "stop", "abort", "reset", "logout"} - reached
    assert not missing, f"not reached by Tab: {missing}"
    page.screenshot("execute")
    page.screenshot("execute-tablet", (820, 1180))
    page.screenshot("execute")

    # Without the token, or with a wrong one: 401, and the cell goes on.
    for tok in (None, "wrong"):
        code, body_json = post("hold", tok)
        assert code == 401 and body_json["ok"] is False, (code, body_json)
    time.sleep(0.5)  # long enough for a hold to show, were one taken (the page refreshes every 200 ms)
    assert text("state") == "Execute", text("state")

    # The Hold button, confirmation accepted: the cell holds (the page's session cookie, no token); the
    # hold is listed apart from the faults.
    page.click_confirmed("hold", "hold the cell?", "hold: accepted")
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Held"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "stops"), "hold commanded by web"))
    assert text("faults") == "none", text("faults")
    page.screenshot("held")

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

    # The Stop button ends the run.
    driver.find_element(By.ID, "stop").click()
    wait.until(EC.alert_is_present()).accept()
    try:
        rc = proc.wait(timeout=60)
    except subprocess.TimeoutExpired:
        fail("cellctl did not end after the stop")
finally:
    driver.quit()

# Ended by the operator: 130 — or 1, as this run latched a fault before (cellctl run's exit status
# names the run's first fault even when the operator stopped it after a reset).
if rc not in (1, 130):
    fail(f"exit {rc}, expected 130 (ended by the operator) or 1 (a fault before)")
with open(os.path.join(out, "run", "journal.jsonl")) as f:
    journal = f.read()
if not re.search(r'"command":"stop","event":"command","source":"web [^"]*\(session #1\)"', journal):
    fail("the journal has no stop from the page's session")
print("operator page: keyboard login, fault with remedies and reset, axes, devices, trend, Tab, refused without "
      "token, hold by button, metrics, stop by button, figures — passed")
