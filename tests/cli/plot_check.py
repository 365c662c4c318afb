#!/usr/bin/env python3
"""Checks a run record's plots as a person would see them.

usage: plot_check.py RUN_DIR AXIS_NAME...

- plot.svg renders to PNG with rsvg-convert (Debian librsvg2-bin) and the PNG is a picture of the
  SVG's size;
- every tick label is a round number: within each scale the ticks are equally spaced by 1, 2 or 5
  times a power of ten and each label is a multiple of that step;
- the legend names every axis given, with its SCU and planned curves, the spindle's set and actual;
- every step the journal started has its boundary and its label whole (its box inside the plot area,
  overlapping no other label in its lane);
- plot.html holds its data and script and no http:// or https:// reference (it opens offline).
"""
import math
import re
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

run_dir, axes = sys.argv[1], sys.argv[2:]
svg_path, png_path, html_path = f"{run_dir}/plot.svg", f"{run_dir}/plot.png", f"{run_dir}/plot.html"
failures = []

subprocess.run(["rsvg-convert", "-o", png_path, svg_path], check=True)
with open(png_path, "rb") as f:
    head = f.read(24)
if head[:8] != b"\x89PNG\r\n\x1a\n":
    failures.append("rsvg-convert did not write a PNG")
width, height = struct.unpack(">II", head[16:24])
root = ET.parse(svg_path).getroot()
if (width, height) != (int(float(root.get("width"))), int(float(root.get("height")))):
    failures.append(f"PNG is {width}x{height}, the SVG says {root.get('width')}x{root.get('height')}")

ns = "{http://www.w3.org/2000/svg}"
texts = list(root.iter(ns + "text"))
ticks = [t for t in texts if t.get("class") == "tick"]
if len(ticks) < 20:
    failures.append(f"only {len(ticks)} tick labels")

scales = {}
for t in ticks:
    scales.setdefault(t.get("data-scale"), []).append(t.text)
for key, labels in scales.items():
    if not all(re.fullmatch(r"-?\d+(\.\d+)?", s) for s in labels):
        failures.append(f"scale {key}: labels that are not plain numbers: {labels}")
        continue
    values = sorted(float(s) for s in labels)
    steps = {round(b - a, 9) for a, b in zip(values, values[1:])}
    if len(steps) != 1:
        failures.append(f"scale {key}: uneven ticks {labels}")
        continue
    step = steps.pop()
    mantissa = step / 10 ** math.floor(math.log10(step))
    if not any(abs(mantissa - m) < 1e-6 for m in (1, 2, 5)):
        failures.append(f"scale {key}: step {step} is not 1, 2 or 5 × 10^k: {labels}")
    if any(abs(v / step - round(v / step)) > 1e-6 for v in values):
        failures.append(f"scale {key}: labels off the step {step}: {labels}")

legend = {t.text for t in texts if t.get("class") == "legend"}
wanted = [f"{a} {what}" for a in axes for what in ("planned", "SCU")] + ["spindle set", "spindle actual"]
for w in wanted:
    if w not in legend:
        failures.append(f"legend lacks '{w}' (has {sorted(legend)})")
# Every step the journal started: its boundary and its label whole, inside the plot area, apart from the
# others in its lane.
import json
started = set()
with open(f"{run_dir}/journal.jsonl", encoding="utf-8") as f:
    for line in f:
        j = json.loads(line)
        if j.get("event") == "step_started":
            started.add(j.get("step"))
frames = [r for r in root.iter(ns + "rect") if r.get("fill") == "none"]
left = float(frames[0].get("x"))
right = left + float(frames[0].get("width"))
boxes = []
for g in root.iter(ns + "g"):
    if g.get("class") != "step":
        continue
    label = g.find(ns + "text")
    if g.find(ns + "line") is None or label is None or label.get("class") != "step-label":
        failures.append(f"step {g.get('data-step')}: no boundary or no label")
        continue
    x, w, y = float(label.get("x")), float(label.get("textLength")), float(label.get("y"))
    if not label.text or not label.text.startswith(g.get("data-step") + " "):
        failures.append(f"step {g.get('data-step')}: label '{label.text}'")
    if x < left or x + w > right:
        failures.append(f"step label '{label.text}' [{x}, {x + w}] outside the plot area [{left}, {right}]")
    boxes.append((y, x, x + w, label.text))
if len(boxes) != len(started):
    failures.append(f"{len(boxes)} step labels for {len(started)} steps started")
for i, a in enumerate(boxes):
    for b in boxes[i + 1:]:
        if a[0] == b[0] and a[1] < b[2] and b[1] < a[2]:
            failures.append(f"step labels '{a[3]}' and '{b[3]}' overlap")

html = open(html_path, encoding="utf-8").read()
for ref in re.findall(r"https?://\S{0,40}", html):
    failures.append(f"plot.html refers to the network: {ref}")
if '<script id="data" type="application/json">' not in html or "addEventListener(\"wheel\"" not in html:
    failures.append("plot.html lacks its data or its zoom")

for f in failures:
    print("FAIL:", f)
print(f"{len(ticks)} tick labels in {len(scales)} scales, {len(legend)} legend entries, {len(boxes)} step labels, "
      f"PNG {width}x{height}")
sys.exit(1 if failures else 0)
