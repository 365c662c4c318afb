#!/usr/bin/python3
"""The operator page of a standing controller in a real browser (Debian's chromium, headless, driven by
chromium-driver and python3-selenium) against `cellctl serve --virtual-time --http`: the jobs started
from the page (Home, Teach-In, Start from the recipe list), each behind a confirmation that says what
moves, the commands of a job in progress, and the run history.

usage: serve_page_test.py CELLCTL CONFIG RECIPES_DIR OUT_DIR

Works on a copy of CONFIG in OUT_DIR, with the state folder OUT_DIR/state and a recipes folder
OUT_DIR/recipes (short.yaml and bad-recipe.yaml from RECIPES_DIR, and a long one). Checks, each wait
on a condition with a time-out:
 - before any job: the axes' SCU and encoder positions and every device's link figures, as serve read
   the cell when it started (figure OUT_DIR/idle-before-jobs.png);
 - the Start list: every recipe with its steps and the planner's planned time (from where the axes stand),
   the invalid one disabled with why;
 - Idle: Hold disabled with its reason; a dismissed confirmation sends nothing;
 - Home (confirmed) homes the cell to Complete; Reset brings it back to Idle (figures OUT_DIR/idle.png
   at 1366×768, OUT_DIR/idle-tablet.png at 820×1180); Teach-In over 100 mm from 5 mm is taught and
   written into the dry run's config (STATE/config.dry-run.yaml), the cell's config untouched; Start of
   the recipe picked from the list runs it to Complete;
 - the run history: the three runs newest first, each complete, each device's safe state observed, the
   plot and the report of a run served, and none of the lists or records without the token (401);
 - a long recipe: Hold, Unhold, Abort, Clear and Reset by their buttons back to Idle, each button
   enabled only where PackML takes it (Reset disabled in Aborted, with why; figure OUT_DIR/aborted.png);
 - /metrics counts the four runs; Log out ends the session (the login form is back);
 - SIGTERM ends cellctl serve with 0.
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import urllib.error
import urllib.request

from selenium.webdriver.common.by import By
from selenium.webdriver.support import expected_conditions as EC
from selenium.webdriver.support.ui import Select, WebDriverWait

from page_session import SLOW_RECIPE, PageSession

cellctl, config_given, recipes_given, out = sys.argv[1:5]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
config = os.path.join(out, "cell.yaml")
shutil.copyfile(config_given, config)
recipes = os.path.join(out, "recipes")
os.makedirs(recipes)
for name in ("short.yaml", "bad-recipe.yaml"):
    shutil.copyfile(os.path.join(recipes_given, name), os.path.join(recipes, name))
with open(os.path.join(recipes, "slow.yaml"), "w") as f:
    f.write(SLOW_RECIPE)
token = "serve-page-token-0815"
with open(os.path.join(out, "token"), "w") as f:
    f.write(token + "\n")

page = PageSession(out)
driver, text = page.driver, page.text
state_dir = os.path.join(out, "state")
page.start([cellctl, "-c", config, "serve", "--virtual-time", "--runs", os.path.join(out, "runs"), "--state-dir",
            state_dir, "--recipes", recipes, "--http-token-file", os.path.join(out, "token")])


def metric(name):
    metrics = page.metrics(token)
    return int(next(line.split()[1] for line in metrics.splitlines() if line.startswith(name + " ")))


def reset_to_idle(wait):
    """Reset (confirmed) after a job: a start is taken only in Idle (PackML)."""
    page.click_confirmed("reset", "reset the cell?", "reset: ")
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Idle"))


def completed(n, what):
    """Waits until n jobs have completed, each its record's summary saying so (the page's "Complete"
    may still be the previous job's; a homing is no product, so PackML's processed count is no measure)."""
    def done():
        runs = json.loads(get("runs")[2])["runs"]
        return len(runs) == n and all(r["outcome"] == "complete" for r in runs)
    page.until(done, what, timeout=60)


def state(name, wait):
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), name))
    page.until(lambda: text("state") == name, f"state {name}")


def get(path):
    req = urllib.request.Request(page.base + path, headers={"X-Cellctl-Token": token})
    with urllib.request.urlopen(req, timeout=10) as r:
        return r.status, r.headers.get("Content-Security-Policy"), r.read().decode()


try:
    driver.get(page.base)
    wait = WebDriverWait(driver, 60)
    page.log_in(token)
    state("Idle", wait)

    # Before any job: the cell as serve read it when it started (nothing moved), every device listed.
    page.until(lambda: re.fullmatch(r"-?\d+\.\d{3}", page.table("axes")[0][2]), "x's SCU position before any job")
    assert re.fullmatch(r"-?\d+\.\d{3}", page.table("axes")[0][3]), page.table("axes")
    assert [d[0] for d in page.table("devices")] == ["scu", "spindle", "encoder"], page.table("devices")
    assert "as read when cellctl serve started" in text("board-age"), text("board-age")
    page.screenshot("idle-before-jobs")

    # The Start list: each recipe of the folder, with its steps and planned time, or why not.
    page.until(lambda: len(Select(driver.find_element(By.ID, "recipe")).options) == 3, "the recipe list")
    options = {o.get_attribute("value"): (o.text, o.is_enabled())
               for o in Select(driver.find_element(By.ID, "recipe")).options}
    # The planner's time from where the emulated axes stand (0 mm; tests/integration/planned_time_test.cpp
    # checks it against runs); the converter's ramps are the emulator's.
    assert options["short"] == ("short — 6 steps, planned 5.5 s", True), options
    assert options["slow"] == ("slow — 10 steps, planned 36000 s", True), options
    assert options["bad-recipe"][0].startswith("bad-recipe — not valid: ") and not options["bad-recipe"][1], options

    # Idle takes no hold (the button says why); a dismissed confirmation sends nothing.
    page.button_disabled_because("hold", "hold is taken only in Execute")
    page.button_disabled_because("clear", "clear is taken only in Aborted")
    driver.find_element(By.ID, "home").click()
    wait.until(EC.alert_is_present()).dismiss()
    assert metric("cellctl_web_commands_total") == 0 and metric("cellctl_runs_total") == 0, \
        (metric("cellctl_web_commands_total"), metric("cellctl_runs_total"))

    page.click_confirmed("home", "The axes MOVE", "home: started: homing")
    completed(1, "homing to complete")
    wait.until(EC.text_to_be_present_in_element((By.ID, "mode"), "dry-run"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "recipe-now"), "home"))
    state("Complete", wait)
    page.button_disabled_because("start", "reset first")
    reset_to_idle(wait)
    page.until(lambda: page.table("axes")[0][4] == "yes", "x homed by the record after homing")
    page.screenshot("idle")
    page.screenshot("idle-tablet", (820, 1180))

    driver.find_element(By.ID, "ti-from").send_keys("5")
    page.click_confirmed("teach-in", "the verified result is written into the cell config", "teach-in: started: Teach-In")
    completed(2, "the Teach-In to complete")
    wait.until(EC.text_to_be_present_in_element((By.ID, "recipe-now"), "teach-in x"))
    # A dry run (serve --virtual-time) writes the dry run's copy, never the cell's config (issue 22);
    # the job writes it once its record is closed.
    page.until(lambda: os.path.exists(os.path.join(state_dir, "config.dry-run.yaml")), "the dry run's config")
    with open(os.path.join(state_dir, "config.dry-run.yaml")) as f:
        assert "measuring_units: " in f.read(), "the Teach-In did not write the dry run's config"
    with open(config) as f, open(config_given) as g:
        assert f.read() == g.read(), "a dry-run Teach-In changed the cell's config"
    reset_to_idle(wait)

    Select(driver.find_element(By.ID, "recipe")).select_by_value("short")
    page.click_confirmed("start", "Start recipe short?", "start: started: recipe 'short'")
    completed(3, "the recipe to complete")
    wait.until(EC.text_to_be_present_in_element((By.ID, "recipe-now"), "short-compare"))
    state("Complete", wait)

    # The run history: newest first, each with its outcome, safe states, plot and report.
    page.until(lambda: len(page.table("runs")) == 3 and page.table("runs")[0][1] == "short-compare", "the run history")
    runs = page.table("runs")
    assert [r[0].split("-")[0] for r in runs] == ["short", "teach", "home"], runs
    assert all(r[2] == "complete" and r[4] == "plot" and r[5] == "report" for r in runs), runs
    page.until(lambda: [d[6] for d in page.table("devices")] == ["observed"] * 3, "the devices' safe states")
    status, csp, plot = get(f"runs/{runs[0][0]}/plot.html")
    assert status == 200 and "<script" in plot, plot[:200]
    assert csp.startswith("sandbox"), csp
    status, _, report = get(f"runs/{runs[0][0]}/report")
    assert status == 200 and "outcome: complete" in report, report[:400]
    # The lists and the records are the session's or the token's only.
    for path in ("recipes", "runs", f"runs/{runs[0][0]}/report", f"runs/{runs[0][0]}/plot.html"):
        try:
            urllib.request.urlopen(page.base + path, timeout=10)
            raise AssertionError(f"/{path} answered without the token")
        except urllib.error.HTTPError as e:
            assert e.code == 401, (path, e.code)
    reset_to_idle(wait)

    # A job in progress: Hold, Unhold, Abort, Clear, Reset by their buttons, each as PackML allows.
    Select(driver.find_element(By.ID, "recipe")).select_by_value("slow")
    page.click_confirmed("start", "Start recipe slow?", "start: started: recipe 'slow'")
    state("Execute", wait)
    page.button_disabled_because("unhold", "unhold is taken only in Held or Holding")
    page.click_confirmed("hold", "hold the cell?", "hold: accepted")
    state("Held", wait)
    page.click_confirmed("unhold", "unhold the cell?", "unhold: unholding")
    state("Execute", wait)
    page.click_confirmed("abort", "emergency stop", "abort: ")
    state("Aborted", wait)
    page.screenshot("aborted")
    page.button_disabled_because("reset", "clear first")
    page.button_disabled_because("abort", "aborting or aborted already")
    page.click_confirmed("clear", "clear the cell?", "clear: ")
    state("Stopped", wait)
    reset_to_idle(wait)
    assert metric("cellctl_runs_total") == 4, metric("cellctl_runs_total")

    driver.find_element(By.ID, "logout").click()
    wait.until(EC.visibility_of_element_located((By.ID, "login")))
finally:
    driver.quit()

page.proc.send_signal(signal.SIGTERM)
try:
    rc = page.proc.wait(timeout=60)
except subprocess.TimeoutExpired:
    page.fail("cellctl serve did not end after SIGTERM")
if rc != 0:
    page.fail(f"exit {rc}, expected 0 (SIGTERM with no job in progress)")
print("serve page: recipe list, Home, Teach-In, Start, run history with plot and report, Hold, Unhold, Abort, "
      "Clear, Reset by button with confirmation, log out, figures — passed")
