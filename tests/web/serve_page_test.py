#!/usr/bin/python3
"""The operator page of a standing controller in a real browser (Debian's chromium, headless, driven by
chromium-driver and python3-selenium) against `cellctl serve --virtual-time --http`: the page's Home,
Teach-In and Start buttons, each behind a confirmation that says what moves, start jobs one at a time.

usage: serve_page_test.py CELLCTL CONFIG RECIPES_DIR OUT_DIR

Works on a copy of CONFIG in OUT_DIR, with the state folder OUT_DIR/state. Checks: the page shows
Idle with no job; a dismissed confirmation sends nothing; Home (confirmed) homes the cell to Complete;
Reset brings it back to Idle (a start is taken only there); Teach-In over 100 mm from 5 mm (confirmed)
is taught and written into the dry run's config (STATE/config.dry-run.yaml), the cell's config untouched; after another Reset, Start of a recipe runs it to Complete; /metrics counts the three runs; a screenshot is saved (OUT_DIR/serve_page.png);
SIGTERM ends cellctl serve with 0. Every wait is on a condition with a time-out.
"""
import os
import shutil
import signal
import subprocess
import sys

from selenium.webdriver.common.by import By
from selenium.webdriver.support import expected_conditions as EC
from selenium.webdriver.support.ui import WebDriverWait

from page_session import PageSession

cellctl, config_given, recipes, out = sys.argv[1:5]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
config = os.path.join(out, "cell.yaml")
shutil.copyfile(config_given, config)
token = "serve-page-token-0815"
with open(os.path.join(out, "token"), "w") as f:
    f.write(token + "\n")

page = PageSession(out)
driver = page.driver
state_dir = os.path.join(out, "state")
page.start([cellctl, "-c", config, "serve", "--virtual-time", "--runs", os.path.join(out, "runs"), "--state-dir",
            state_dir, "--recipes", recipes, "--http-token-file", os.path.join(out, "token")])


def text(element_id):
    return driver.find_element(By.ID, element_id).text


def confirm_and_answer(button, confirmation_part, answer_part, wait):
    """Clicks `button`, checks and accepts its confirmation, waits for the answer."""
    driver.find_element(By.ID, button).click()
    alert = wait.until(EC.alert_is_present())
    assert confirmation_part in alert.text, alert.text
    alert.accept()
    wait.until(EC.text_to_be_present_in_element((By.ID, "answer"), answer_part))


def metric(name):
    metrics = page.metrics(token)
    return int(next(line.split()[1] for line in metrics.splitlines() if line.startswith(name + " ")))


def reset_to_idle(wait):
    """Reset (confirmed) after a job: a start is taken only in Idle (PackML)."""
    confirm_and_answer("reset", "reset the cell?", "reset: ", wait)
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Idle"))


def completed(n, what):
    """Waits until n jobs have completed (PackML ProdProcessedCount): the page's "Complete" may still be
    the previous job's."""
    page.until(lambda: metric("cellctl_processed_total") == n, what, timeout=60)


try:
    driver.get(page.base)
    wait = WebDriverWait(driver, 60)
    page.log_in(token)
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Idle"))

    # A dismissed confirmation sends nothing: the Hold confirmed after it is the page's first command
    # (a click's request leaves before the next click is handled).
    driver.find_element(By.ID, "home").click()
    wait.until(EC.alert_is_present()).dismiss()
    confirm_and_answer("hold", "hold the cell?", "hold: hold is not possible in state Idle", wait)
    assert metric("cellctl_web_commands_total") == 1 and metric("cellctl_runs_total") == 0, \
        (metric("cellctl_web_commands_total"), metric("cellctl_runs_total"))

    confirm_and_answer("home", "The axes MOVE", "home: started: homing", wait)
    completed(1, "homing to complete")
    wait.until(EC.text_to_be_present_in_element((By.ID, "mode"), "home"))
    reset_to_idle(wait)

    driver.find_element(By.ID, "ti-from").send_keys("5")
    confirm_and_answer("teach-in", "the verified result is written into the cell config", "teach-in: started: Teach-In", wait)
    completed(2, "the Teach-In to complete")
    wait.until(EC.text_to_be_present_in_element((By.ID, "mode"), "teach-in x"))
    # A dry run (serve --virtual-time) writes the dry run's copy, never the cell's config (issue 22).
    with open(os.path.join(state_dir, "config.dry-run.yaml")) as f:
        assert "measuring_units: " in f.read(), "the Teach-In did not write the dry run's config"
    with open(config) as f, open(config_given) as g:
        assert f.read() == g.read(), "a dry-run Teach-In changed the cell's config"
    reset_to_idle(wait)

    recipe = driver.find_element(By.ID, "recipe")
    recipe.clear()
    recipe.send_keys("short")
    confirm_and_answer("start", "Start recipe short?", "start: started: recipe 'short'", wait)
    completed(3, "the recipe to complete")
    wait.until(EC.text_to_be_present_in_element((By.ID, "mode"), "short-compare"))
    wait.until(EC.text_to_be_present_in_element((By.ID, "state"), "Complete"))
    driver.save_screenshot(os.path.join(out, "serve_page.png"))
    assert metric("cellctl_runs_total") == 3, metric("cellctl_runs_total")
finally:
    driver.quit()

page.proc.send_signal(signal.SIGTERM)
try:
    rc = page.proc.wait(timeout=60)
except subprocess.TimeoutExpired:
    page.fail("cellctl serve did not end after SIGTERM")
if rc != 0:
    page.fail(f"exit {rc}, expected 0 (SIGTERM with no job in progress)")
print("serve page: Home, Teach-In and Start by button with confirmation, metrics, screenshot — passed")
