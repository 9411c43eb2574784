#!/usr/bin/python3
"""The studio in a real browser (headless Chromium through Selenium), as a user drives it.

Starts `pleinair studio`, opens its page and checks: it loads without a console error; a tree
control changes the picture, and the picture equals what the command the page shows paints
(pixel for pixel, through idiff); turning the camera changes it; "keep" writes a preset that
`pleinair tree` reads back to the same tree; a bad value puts the command line's message beside
its control and keeps the last picture; requests from another origin or host, and oversized
ones, are refused; a shot scrubs along its timeline, its previews drafts by default. Screenshots
go to --artifacts.

Run by `make test-studio`: /usr/bin/python3 tests/studio/test_studio.py --pleinair build/pleinair
"""
import argparse
import base64
import filecmp
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

# The studio is on loopback: no proxy from the environment may stand between.
OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))
FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


class Studio:
    """A `pleinair studio` process on a free port, stopped with Ctrl-C."""

    def __init__(self, pleinair, args, cwd):
        self.proc = subprocess.Popen([pleinair, "studio", "--port", "0"] + args, cwd=cwd,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()
        m = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        if not m:
            self.proc.kill()
            raise RuntimeError("the studio did not start: " + line + self.proc.stderr.read())
        self.port = int(m.group(1))
        self.url = f"http://127.0.0.1:{self.port}/"

    def stop(self):
        self.proc.send_signal(signal.SIGINT)
        try:
            out, err = self.proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return False, "did not stop within 30 s"
        return self.proc.returncode == 0 and "stopped" in out, err

    def request(self, path, data=None, headers=None):
        req = urllib.request.Request(self.url.rstrip("/") + path, data=data,
                                     headers=headers or {})
        try:
            with OPENER.open(req, timeout=60) as r:
                return r.status, r.read()
        except urllib.error.HTTPError as e:
            return e.code, e.read()


def browser():
    o = webdriver.ChromeOptions()
    for a in ["--headless=new", "--no-sandbox", "--disable-gpu", "--no-proxy-server",
              "--window-size=1500,950", "--disable-dev-shm-usage"]:
        o.add_argument(a)
    o.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)


def frames_shown(d):
    return int(d.execute_script("return Number(document.body.dataset.frames || 0)"))


def wait_full_frame(d, after, timeout=90):
    """Waits until a full-size frame newer than `after` frames is shown and the input rests."""
    def ready(_):
        return d.execute_script(
            "const i = document.getElementById('picture');"
            "return Number(document.body.dataset.frames || 0) > arguments[0] &&"
            " i.dataset.preview === '0' && i.complete && i.naturalWidth > 0", after)
    WebDriverWait(d, timeout).until(lambda _: ready(_) if frames_shown(d) > after else False)
    # A later full frame may be on its way (changes still queued): let it land.
    time.sleep(0.4)
    WebDriverWait(d, timeout).until(ready)


def show_step(d, step):
    """Chooses one of the thesis's steps (trunk, leaves, whole) and waits for its full frame."""
    n = frames_shown(d)
    d.execute_script("const s = document.getElementById('step'); s.value = arguments[0];"
                     "s.dispatchEvent(new Event('change'));", step)
    wait_full_frame(d, n)


def shown_png(d, path):
    """The bytes of the picture on the page, as the page received them."""
    b64 = d.execute_async_script(
        "const done = arguments[0];"
        "fetch(document.getElementById('picture').src).then(r => r.arrayBuffer()).then(b => {"
        " let s = ''; const u = new Uint8Array(b);"
        " for (let i = 0; i < u.length; i++) s += String.fromCharCode(u[i]);"
        " done(btoa(s)); });")
    with open(path, "wb") as f:
        f.write(base64.b64decode(b64))


def same_pixels(a, b):
    r = subprocess.run(["idiff", "-fail", "0", "-failpercent", "0", "-warn", "0", a, b],
                       capture_output=True, text=True)
    return r.returncode == 0, r.stdout.strip().splitlines()[-1:] if r.stdout else r.stderr


def set_control(d, pointer, value):
    """Types a value into the number box of the control at `pointer` and commits it."""
    d.execute_script(
        "const row = document.querySelector(`.row[data-pointer='${arguments[0]}']`);"
        "const box = row.querySelector('input[type=number]');"
        "box.value = arguments[1]; box.dispatchEvent(new Event('change'));", pointer, value)


def console_errors(d, refused_ok=False):
    """SEVERE console entries; with refused_ok, less the network line Chromium logs for the
    400 answer to a refused value (the refusal under test)."""
    return [e for e in d.get_log("browser") if e.get("level") == "SEVERE" and not (
        refused_ok and "/api/change" in e.get("message", "") and "400" in e.get("message", ""))]


def run_command(pleinair, command, out, cwd):
    words = shlex.split(command)
    check(words[:2] == ["pleinair", "render"], "the page shows a pleinair render command")
    words[0] = pleinair
    words[words.index("-o") + 1] = out
    r = subprocess.run(words, cwd=cwd, capture_output=True, text=True)
    check(r.returncode == 0, "the shown command runs: " + r.stderr.strip())


def test_tree(pleinair, artifacts, work):
    save_to = os.path.join(work, "kept")
    studio = Studio(pleinair, ["--preset", "oak", "--save-to", save_to], work)
    try:
        use_tree(studio, pleinair, artifacts, work, save_to)
    finally:
        ok, err = studio.stop()
    check(ok, "Ctrl-C stops the studio cleanly " + str(err)[:200])


def use_tree(studio, pleinair, artifacts, work, save_to):
    d = browser()
    try:
        d.get(studio.url)
        wait_full_frame(d, 0)
        d.save_screenshot(os.path.join(artifacts, "studio-tree.png"))
        check(not console_errors(d), f"the page loads without a console error {console_errors(d)}")
        rows = d.find_elements(By.CSS_SELECTOR, ".row[data-pointer^='/families/tree/tree/']")
        check(len(rows) > 40, f"every tree key has a control ({len(rows)})")
        tipped = d.find_element(By.CSS_SELECTOR,
                                ".row[data-pointer='/families/tree/tree/trunk/taper'] label")
        check("Range" in (tipped.get_attribute("title") or ""), "a control's tooltip gives its range")

        before = os.path.join(work, "before.png")
        shown_png(d, before)
        n = frames_shown(d)
        set_control(d, "/families/tree/tree/trunk/taper", "0.8")
        wait_full_frame(d, n)
        changed = os.path.join(work, "changed.png")
        shown_png(d, changed)
        check(not same_pixels(before, changed)[0], "a tree control changes the picture")
        command = d.find_element(By.ID, "command").get_attribute("value")
        check("/families/tree/tree/trunk/taper/base=0.8" in command,
              "the command carries the change: " + command)
        painted = os.path.join(work, "painted.png")
        run_command(pleinair, command, painted, work)
        same, why = same_pixels(changed, painted)
        check(same, f"the picture equals what the shown command paints {why}")
        d.save_screenshot(os.path.join(artifacts, "studio-tree-changed.png"))

        n = frames_shown(d)
        vp = d.find_element(By.ID, "viewport")
        ActionChains(d).move_to_element(vp).click_and_hold().move_by_offset(120, 10) \
            .move_by_offset(60, 0).release().perform()
        wait_full_frame(d, n)
        turned = os.path.join(work, "turned.png")
        shown_png(d, turned)
        check(not same_pixels(changed, turned)[0], "turning the camera changes the picture")
        command = d.find_element(By.ID, "command").get_attribute("value")
        run_command(pleinair, command, painted, work)
        check(same_pixels(turned, painted)[0], "after a turn, the picture equals the command's")

        # The thesis's steps: the trunk alone, then back to the whole tree.
        show_step(d, 'trunk')
        trunk = os.path.join(work, "trunk.png")
        shown_png(d, trunk)
        command = d.find_element(By.ID, "command").get_attribute("value")
        check("/leaves/probability=0" in command and "/branches/enabled=false" in command,
              "showing the trunk alone is the same overrides on the command line")
        d.save_screenshot(os.path.join(artifacts, "studio-tree-trunk.png"))
        show_step(d, 'leaves')
        command = d.find_element(By.ID, "command").get_attribute("value")
        check("/render/bark_coverage=0" in command and "/leaves/probability" not in command,
              "the leaves alone: no bark strokes, the trunk's overrides gone")
        d.save_screenshot(os.path.join(artifacts, "studio-tree-leaves.png"))
        show_step(d, 'whole')
        whole = os.path.join(work, "whole.png")
        shown_png(d, whole)
        check(same_pixels(whole, turned)[0], "back to the whole tree, the picture is as before")

        d.find_element(By.ID, "contact").click()
        WebDriverWait(d, 60).until(lambda _: d.execute_script(
            "const i = document.getElementById('sheet-image');"
            "return !document.getElementById('sheet').hidden && i.complete && i.naturalWidth > 0"))
        d.save_screenshot(os.path.join(artifacts, "studio-tree-contact-sheet.png"))
        d.find_element(By.ID, "sheet-close").click()

        d.find_element(By.ID, "keep").click()
        WebDriverWait(d, 30).until(
            lambda _: "kept as" in d.find_element(By.ID, "status").text)
        kept = d.find_element(By.ID, "status").text.split("kept as ", 1)[1].strip()
        check(os.path.dirname(kept) == save_to and os.path.exists(kept),
              "keep writes a preset into --save-to: " + kept)
        a, b = os.path.join(work, "kept-tree"), os.path.join(work, "set-tree")
        subprocess.run([pleinair, "tree", "--preset", kept, "--seed", "1", "--out", a], check=True,
                       capture_output=True)
        subprocess.run([pleinair, "tree", "--preset", "oak", "--seed", "1", "--set",
                        "/trunk/taper/base=0.8", "--out", b], check=True, capture_output=True)
        files = sorted(f for f in os.listdir(a) if f.endswith((".obj", ".ply")))
        match, mismatch, errors = filecmp.cmpfiles(a, b, files, shallow=False)
        check(files and not mismatch and not errors,
              f"the kept preset grows the same tree ({len(match)} files the same)")

        shown_seq = d.find_element(By.ID, "picture").get_attribute("data-seq")
        set_control(d, "/families/tree/tree/trunk/taper", "7")
        err = d.find_element(By.CSS_SELECTOR,
                             ".row[data-pointer='/families/tree/tree/trunk/taper'] .error")
        WebDriverWait(d, 30).until(lambda _: err.is_displayed())
        check("/families/tree/tree/trunk/taper/base: must be in [0, 1], got 7" in err.text,
              "a bad value gets the command line's message beside its control: " + err.text)
        time.sleep(1)
        check(d.find_element(By.ID, "picture").get_attribute("data-seq") == shown_seq,
              "the last good picture stays")
        d.save_screenshot(os.path.join(artifacts, "studio-tree-bad-value.png"))
        errors = console_errors(d, refused_ok=True)
        check(not errors, f"no console error after a refused value {errors}")
    finally:
        d.quit()

    status, _ = studio.request("/api/catalog", headers={"Origin": "http://evil.example"})
    check(status == 403, f"another origin is refused ({status})")
    status, _ = studio.request("/", headers={"Host": f"evil.example:{studio.port}"})
    check(status == 403, f"another Host (DNS rebinding) is refused ({status})")
    status, _ = studio.request("/api/change", data=b"{" + b" " * 200000 + b"}",
                               headers={"Content-Type": "application/json"})
    check(status == 413, f"an oversized request is refused ({status})")
    status, _ = studio.request("/api/change", data=b"not json")
    check(status == 400, f"a malformed change is refused ({status})")
    status, _ = studio.request("/../../etc/passwd")
    check(status == 404, f"no path outside the page is served ({status})")
    status, _ = studio.request("/api/frame?frame=abc")
    check(status in (200, 400), f"a still ignores or refuses a frame parameter ({status})")
    status, body = studio.request("/api/change", headers={"Content-Type": "application/json"},
                                  data=b'{"set": {"/families/tree/preset": "/etc/passwd"}}')
    check(status == 400 and b"reads files only from" in body,
          f"a change cannot name a file outside the preset folders ({status})")


def test_scene(pleinair, artifacts, work):
    """A landscape of graftal trees: load, orbit, and a leaf shader key from its panel."""
    studio = Studio(pleinair, ["truffula", "--set", "/camera/width=960",
                               "--set", "/camera/height=540"], work)
    d = browser()
    try:
        d.get(studio.url)
        wait_full_frame(d, 0, timeout=180)
        first = os.path.join(work, "truffula.png")
        shown_png(d, first)
        n = frames_shown(d)
        vp = d.find_element(By.ID, "viewport")
        ActionChains(d).move_to_element(vp).click_and_hold().move_by_offset(-80, 0) \
            .move_by_offset(-40, 0).release().perform()
        wait_full_frame(d, n, timeout=180)
        turned = os.path.join(work, "truffula-turned.png")
        shown_png(d, turned)
        check(not same_pixels(first, turned)[0], "orbiting a scene changes the picture")
        command = d.find_element(By.ID, "command").get_attribute("value")
        painted = os.path.join(work, "truffula-painted.png")
        run_command(pleinair, command, painted, work)
        check(same_pixels(turned, painted)[0], "the scene's picture equals the command's")
        d.save_screenshot(os.path.join(artifacts, "studio-truffula.png"))
        errors = console_errors(d)
        check(not errors, f"the scene's page has no console error {errors}")
    finally:
        d.quit()
        studio.stop()


def test_shot(pleinair, artifacts, work):
    studio = Studio(pleinair, ["tree-dolly"], work)
    d = browser()
    try:
        d.get(studio.url)
        wait_full_frame(d, 0, timeout=180)
        check(d.find_element(By.ID, "timeline").is_displayed(), "a shot has a timeline")
        before = os.path.join(work, "shot-first.png")
        shown_png(d, before)
        n = frames_shown(d)
        t0 = time.time()
        for f in range(2, 22):
            d.execute_script("const s = document.getElementById('frame'); s.value = arguments[0];"
                             "s.dispatchEvent(new Event('input'));", f)
            time.sleep(0.05)
        d.execute_script("document.getElementById('frame').dispatchEvent(new Event('change'))")
        wait_full_frame(d, n, timeout=180)
        shown = frames_shown(d) - n
        print(f"     scrubbing tree-dolly: {shown} frames shown in {time.time() - t0:.2f} s")
        after = os.path.join(work, "shot-later.png")
        shown_png(d, after)
        check(not same_pixels(before, after)[0], "scrubbing the timeline changes the picture")
        command = d.find_element(By.ID, "command").get_attribute("value")
        check("--frame 21" in command, "the command names the frame: " + command)
        painted = os.path.join(work, "shot-painted.png")
        run_command(pleinair, command, painted, work)
        check(same_pixels(after, painted)[0], "the shot's frame equals render --frame's")
        check(d.find_element(By.ID, "draft").is_selected(), "draft previews are on by default")
        req = urllib.request.Request(studio.url + "api/frame?preview=1&draft=1&frame=21")
        with OPENER.open(req, timeout=120) as r:
            status, drafted = r.status, r.headers.get("X-Pleinair-Command", "")
        check(status == 200 and "--preview --draft" in drafted,
              f"a draft preview is painted ({status}) and its command says --draft: {drafted}")
        d.find_element(By.ID, "circles").click()
        d.find_element(By.ID, "explain").click()
        WebDriverWait(d, 30).until(
            lambda _: "sprites" in d.find_element(By.ID, "explain-panel").text)
        d.save_screenshot(os.path.join(artifacts, "studio-shot.png"))
        errors = console_errors(d)
        check(not errors, f"the shot's page has no console error {errors}")
    finally:
        d.quit()
        studio.stop()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pleinair", required=True)
    ap.add_argument("--artifacts", required=True)
    args = ap.parse_args()
    pleinair = os.path.abspath(args.pleinair)
    os.makedirs(args.artifacts, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        test_tree(pleinair, os.path.abspath(args.artifacts), work)
        test_scene(pleinair, os.path.abspath(args.artifacts), work)
        test_shot(pleinair, os.path.abspath(args.artifacts), work)
    print(f"{len(FAILURES)} failed" if FAILURES else "all passed; screenshots in " + args.artifacts)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
