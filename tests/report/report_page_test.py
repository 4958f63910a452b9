#!/usr/bin/env python3
"""The HTML report in headless Chromium (Debian's chromium, driven over the DevTools protocol).

Runs a small hexapod study, exports its report and loads it in Chromium, then checks:
  * no console error and no uncaught exception, at load and after every step;
  * the scatter shows every design; choosing other objectives on the axes redraws it with them;
  * clicking a point pins it, clicking a table row pins another: the comparison shows both, each
    with its machine drawing; clicking again unpins;
  * clicking a heading sorts the designs table; the filter hides designs;
  * the knee table and the knee slice (with the task box) are on the page;
  * brushing: dragging along an axis of the parallel coordinates keeps exactly the designs inside
    the brushed range in the table and fades the others in the scatter; a second axis narrows
    it; the chosen design is among those kept; a click on the axis and "clear brushes" undo it;
  * choosing: for weights, aspiration levels, the knee and the compromise, the design the page
    chooses is the one `pkmopt choose` chooses when run with the command line the page shows
    (the page's rules are a second implementation of optimizer/decision);
  * normalised axes relabel the scatter.
Writes a screenshot of the comparison of two pinned designs to SCRATCH/pinned.png.

Usage: report_page_test.py PKMOPT_BINARY SOURCE_DIR SCRATCH_DIR [--report DIR]
  --report DIR: check DIR/report.html of an existing run (exported with `pkmopt export DIR
  --format html`) instead of running the small study.
"""
import base64
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

import websocket

CHROMIUM = "/usr/bin/chromium"


class Page:
    """One Chromium tab over the DevTools protocol, collecting errors as they come."""

    def __init__(self, ws_url):
        self.ws = websocket.create_connection(ws_url, timeout=60)
        self.next_id = 0
        self.errors = []
        self.events = []

    def _handle(self, message):
        method = message.get("method")
        params = message.get("params", {})
        if method == "Runtime.exceptionThrown":
            d = params["exceptionDetails"]
            self.errors.append("exception: " + d.get("exception", {}).get("description",
                                                                          d.get("text", "")))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            self.errors.append("console.error: " + " ".join(
                str(a.get("value", a.get("description", ""))) for a in params.get("args", [])))
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            self.errors.append("log: " + params["entry"].get("text", ""))
        elif method:
            self.events.append(method)

    def call(self, method, **params):
        self.next_id += 1
        my_id = self.next_id
        self.ws.send(json.dumps({"id": my_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv())
            if message.get("id") == my_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self._handle(message)

    def wait_for(self, event, seconds=30):
        deadline = time.time() + seconds
        while time.time() < deadline:
            if event in self.events:
                return
            self._handle(json.loads(self.ws.recv()))
        raise TimeoutError(event)

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True,
                      awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expression}: {r['exceptionDetails']}")
        return r["result"].get("value")


def start_chromium(profile):
    proc = subprocess.Popen(
        [CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", "--remote-allow-origins=*", "--remote-debugging-port=0",
         "--window-size=1500,1200", f"--user-data-dir={profile}", "about:blank"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    port_file = pathlib.Path(profile) / "DevToolsActivePort"
    deadline = time.time() + 60
    while not port_file.exists() or not port_file.read_text().strip():
        if time.time() > deadline or proc.poll() is not None:
            proc.kill()
            raise RuntimeError("chromium did not start (no DevToolsActivePort)")
        time.sleep(0.1)
    port = int(port_file.read_text().split()[0])
    targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list"))
    page = next(t for t in targets if t["type"] == "page")
    return proc, page["webSocketDebuggerUrl"]


def click(selector):
    return (f"(function () {{ const e = document.querySelector({json.dumps(selector)}); "
            f"if (!e) return false; e.dispatchEvent(new MouseEvent('click', {{bubbles: true}})); "
            f"return true; }})()")


BRUSH = ("(function (k, a, b) {"
         " const hit = document.querySelector('#parallel .axis-hit[data-axis=\"' + k + '\"]');"
         " if (!hit) return false;"
         " const r = hit.getBoundingClientRect(), x = r.x + r.width / 2;"
         " const ev = function (type, t) { return new MouseEvent(type, {bubbles: true,"
         " clientX: x, clientY: r.y + t * r.height}); };"
         " hit.dispatchEvent(ev('mousedown', a)); window.dispatchEvent(ev('mousemove', b));"
         " window.dispatchEvent(ev('mouseup', b)); return true; })")
BRUSH_RANGE = ("(function (k) { const b = document.querySelector("
               "'#parallel rect.brush[data-axis=\"' + k + '\"]'); return b ? "
               "[+b.getAttribute('data-lo'), +b.getAttribute('data-hi')] : null; })")


def check_brushing(page, front, designs, check, order):
    """Brushes on the parallel coordinates filter the table and fade the scatter."""
    page.js("(function () { const f = document.getElementById('filter'); f.value = ''; "
            "f.dispatchEvent(new Event('input')); })()")
    names = [o["name"] for o in front["objectives"]]
    check(page.js(BRUSH + "(0, 0.02, 0.5)"), "an axis to brush")
    first = page.js(BRUSH_RANGE + "(0)")
    check(first is not None, f"the brush is drawn: {first}")
    if first is None:
        return

    def inside(d, k, r):
        v = d["objectives"][names[k]]
        return v is not None and r[0] <= v <= r[1]

    kept = [d["id"] for d in front["designs"] if inside(d, 0, first)]
    rows = page.js(order)
    check(sorted(rows) == sorted(kept) and 0 < len(kept) < len(designs),
          f"one brush keeps the {len(kept)} designs inside it in the table ({len(rows)} rows)")
    faded = page.js("document.querySelectorAll('#scatter circle.pt.out').length")
    check(faded == len(designs) - len(kept), f"the scatter fades the others ({faded})")
    page.js(BRUSH + "(1, 0.0, 0.8)")
    second = page.js(BRUSH_RANGE + "(1)")
    both = [d["id"] for d in front["designs"] if inside(d, 0, first) and
            (second is not None and inside(d, 1, second))]
    rows = page.js(order)
    check(second is not None and sorted(rows) == sorted(both) and len(both) <= len(kept),
          f"a second brush keeps the {len(both)} designs inside both ({len(rows)} rows)")
    chosen = page.js("(function () { const c = document.getElementById('chosen-id'); "
                     "return c ? c.textContent : null; })()")
    feasible_both = [d["id"] for d in front["designs"] if d["id"] in both and d["feasible"]]
    check(chosen in feasible_both if feasible_both else chosen is None,
          f"the chosen design {chosen} is a feasible one inside the brushes")
    page.js(BRUSH + "(1, 0.4, 0.4)")  # a click: clears that axis
    check(page.js(BRUSH_RANGE + "(1)") is None and sorted(page.js(order)) == sorted(kept),
          "a click on the axis clears its brush")
    page.js(click("#clear-brushes"))
    check(len(page.js(order)) == len(designs), "clear brushes shows every design again")


def check_choosing(page, front, binary, out, scratch, check):
    """Each rule chooses in the page what `pkmopt choose` chooses with the command shown."""
    data = page.js("JSON.parse(document.getElementById('report-data').textContent)")
    m = len(front["objectives"])
    feasible = [d for d in front["designs"] if d["feasible"]]
    middle = []
    for o in data["objectives"]:
        values = [d["objectives"][o["name"]] for d in feasible]
        middle.append(f"{0.5 * (min(values) + max(values)) * o['scale']:.6g}")
    cases = [("weights", "w", ["2", "1", "0", "1"][:m] + ["1"] * max(0, m - 4)),
             ("weights", "w", ["0", "0", "1"] + ["0"] * max(0, m - 3)),
             ("reference", "z", middle), ("knee", None, None), ("compromise", None, None)]
    for rule, cls, values in cases:
        script = ("(function () { const r = document.getElementById('rule'); "
                  f"r.value = '{rule}'; r.dispatchEvent(new Event('change'));")
        if cls:
            for k, v in enumerate(values):
                script += (f" const i{k} = document.querySelector('#choose-inputs input.{cls}"
                           f"[data-k=\"{k}\"]'); i{k}.value = '{v}';"
                           f" i{k}.dispatchEvent(new Event('input'));")
        script += (" return [document.getElementById('chosen-id').textContent,"
                   " document.getElementById('chosen-command').textContent]; })()")
        page_id, command = page.js(script)
        args = [str(out) if a == "DIR" else a for a in command.split()[2:]]
        r = subprocess.run([str(binary), "choose"] + args +
                           ["--out", str(scratch / "chosen.yaml")], capture_output=True, text=True)
        cli_id = r.stdout.split(",")[0].removeprefix("choose: ") if r.returncode == 0 else r.stderr
        check(page_id == cli_id, f"{rule} {values}: the page chooses {page_id}, "
                                 f"`{command}` chooses {cli_id}")
        if rule in ("knee", "compromise"):
            check(page_id == front[rule], f"the page's {rule} is pareto.json's ({front[rule]})")
    look = page.js("document.getElementById('look-first').textContent")
    check(front["compromise"] in look, f"the designs to look at first: {look}")


def main():
    binary, source, scratch = (pathlib.Path(a).resolve() for a in sys.argv[1:4])
    if scratch.exists():
        shutil.rmtree(scratch)
    scratch.mkdir(parents=True)
    if "--report" in sys.argv[4:]:
        out = pathlib.Path(sys.argv[sys.argv.index("--report") + 1]).resolve()
    else:
        study = (source / "studies/library/hexapod-milling.yaml").read_text()
        study = re.sub(r"population: \d+", "population: 40", study)
        study = re.sub(r"generations: \d+", "generations: 20", study)
        study = re.sub(r"resolution: [0-9.]+", "resolution: 0.1", study)
        (scratch / "study.yaml").write_text(study)
        out = scratch / "run"
        for args in (["run", str(scratch / "study.yaml"), "--out", str(out), "--no-progress"],
                     ["export", str(out), "--format", "html"]):
            r = subprocess.run([str(binary)] + args, capture_output=True, text=True)
            if r.returncode != 0:
                print(f"FAIL: pkmopt {' '.join(args)} exited {r.returncode}: {r.stderr}")
                return 1
    front = json.loads((out / "pareto.json").read_text())
    designs = [d["id"] for d in front["designs"]]
    if len(designs) < 3:
        print(f"FAIL: the study's front has {len(designs)} designs, the test needs 3")
        return 1

    failures = []

    def check(condition, what):
        print(("ok   " if condition else "FAIL ") + what)
        if not condition:
            failures.append(what)

    profile = tempfile.mkdtemp(prefix="pkmopt-chromium-")
    proc, ws_url = start_chromium(profile)
    try:
        page = Page(ws_url)
        for domain in ("Runtime.enable", "Log.enable", "Page.enable"):
            page.call(domain)
        page.call("Page.navigate", url=(out / "report.html").as_uri())
        page.wait_for("Page.loadEventFired")
        check(not page.errors, f"no console error at load {page.errors}")
        points = page.js("document.querySelectorAll('#scatter circle.pt').length")
        check(points == len(designs), f"the scatter shows every design ({points} of {len(designs)})")
        x0 = page.js("document.getElementById('x-label').textContent")
        check(x0.startswith(front["objectives"][0]["name"]), f"x axis at load: {x0}")
        # Other objectives on the axes.
        page.js("(function () { const x = document.getElementById('x-axis'); x.value = '2'; "
                "x.dispatchEvent(new Event('change')); const y = document.getElementById('y-axis');"
                " y.value = '3'; y.dispatchEvent(new Event('change')); })()")
        x1 = page.js("document.getElementById('x-label').textContent")
        y1 = page.js("document.getElementById('y-label').textContent")
        check(x1.startswith(front["objectives"][2]["name"]) and
              y1.startswith(front["objectives"][3]["name"]), f"axes chosen: x {x1}, y {y1}")
        # Pin a point of the scatter, then a row of the table.
        check(page.js(click(f"#scatter circle.pt[data-id='{designs[0]}']")), "a point to click")
        check(page.js(click(f"#designs tr[data-id='{designs[1]}']")), "a row to click")
        heads = page.js("Array.from(document.querySelectorAll('#pinned table.compare tr:first-child"
                        " th')).map(function (t) { return t.textContent; })")
        check(heads is not None and len(heads) == 3 and designs[0] in heads[1] and
              designs[1] in heads[2], f"two designs compared side by side: {heads}")
        drawings = page.js("document.querySelectorAll('#pinned svg.machine').length")
        check(drawings == 2, f"each pinned design drawn ({drawings})")
        labelled = page.js(f"Array.from(document.querySelectorAll('#scatter text')).some("
                           f"function (t) {{ return t.textContent.indexOf('1: {designs[0]}') === 0; }})")
        check(labelled, "the pinned point is labelled on the scatter")
        # Screenshot of the comparison.
        box = page.js("(function () { const r = document.getElementById('pinned')"
                      ".getBoundingClientRect(); return [r.x + scrollX, r.y + scrollY, r.width, "
                      "r.height]; })()")
        shot = page.call("Page.captureScreenshot", format="png", captureBeyondViewport=True,
                         clip={"x": box[0], "y": box[1], "width": max(box[2], 10),
                               "height": max(box[3], 10), "scale": 1})
        (scratch / "pinned.png").write_bytes(base64.b64decode(shot["data"]))
        # The page from its top to the end of the comparison: the scatter with the pinned labels.
        page_shot = page.call("Page.captureScreenshot", format="png", captureBeyondViewport=True,
                              clip={"x": 0, "y": 0, "width": 1500,
                                    "height": box[1] + max(box[3], 10), "scale": 1})
        (scratch / "report-pinned.png").write_bytes(base64.b64decode(page_shot["data"]))
        print(f"screenshots: {scratch / 'pinned.png'}, {scratch / 'report-pinned.png'}")
        # Unpin the first again.
        page.js(click(f"#scatter circle.pt[data-id='{designs[0]}']"))
        n = page.js("document.querySelectorAll('#pinned table.compare tr:first-child th').length")
        check(n == 2, f"clicking a pinned point unpins it ({n - 1 if n else 0} left)")
        # Sort by the first column (a parameter) and filter.
        order = ("Array.from(document.querySelectorAll('#designs tr[data-id]'))"
                 ".map(function (r) { return r.getAttribute('data-id'); })")
        name = front["parameters"][0]["name"]
        ascending = [d["id"] for d in sorted(front["designs"], key=lambda d: d["parameters"][name])]
        page.js(click("#designs th[data-sort='0']"))
        check(page.js(order) == ascending, f"sorted by {name}, ascending")
        page.js(click("#designs th[data-sort='0']"))
        descending = [d["id"] for d in sorted(front["designs"],
                                              key=lambda d: -d["parameters"][name])]
        check(page.js(order) == descending, f"sorted by {name}, descending")
        # A condition in display units (mm) on the same parameter keeps the designs above it.
        values = sorted(d["parameters"][name] for d in front["designs"])
        limit = 1e3 * values[len(values) // 2]
        page.js("(function () { const f = document.getElementById('filter'); "
                f"f.value = '{name} >= {limit!r}'; f.dispatchEvent(new Event('input')); }})()")
        expected = sum(1 for v in values if 1e3 * v >= limit)
        rows = page.js("document.querySelectorAll('#designs tr[data-id]').length")
        check(rows == expected, f"the filter {name} >= {limit:.5g} mm leaves {rows} of {expected}")
        page.js("(function () { const f = document.getElementById('filter'); "
                f"f.value = '{designs[2]}'; f.dispatchEvent(new Event('input')); }})()")
        rows = page.js("document.querySelectorAll('#designs tr[data-id]').length")
        check(rows == 1, f"the filter leaves one design ({rows})")
        check(page.js("document.querySelectorAll('#knee-table tr').length") > 5, "the knee table")
        check(page.js("!!document.querySelector('img[alt^=\"workspace slice\"]')"), "the knee slice")
        check_brushing(page, front, designs, check, order)
        check_choosing(page, front, binary, out, scratch, check)
        page.js(click("#normalised"))
        x2 = page.js("document.getElementById('x-label').textContent")
        check("[0 = best, 1 = worst]" in x2, f"normalised axes: {x2}")
        page.js(click("#normalised"))
        check(not page.errors, f"no console error after the steps {page.errors}")
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)
    print(f"{len(failures)} checks failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
