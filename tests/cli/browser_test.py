#!/usr/bin/env python3
"""The web page of `facet step --html` in a real browser: Debian's Chromium, headless, driven through
chromedriver by WebDriver over HTTP (python3's standard library only).

    browser_test.py --facet FACET --work DIR [--chromium PATH] [--chromedriver PATH] MODEL [OPTION...]

Runs `facet step MODEL OPTION... --html DIR/page`, opens DIR/page/index.html, steps through the stages
with the buttons and the keys and checks the stage title follows, clicks a traced pixel of the image and
checks that the page shows that pixel and, word for word and number for number, the history that
`facet step MODEL OPTION... --pixel X,Y --print` prints; then clicks a pixel that was not traced and checks
that the page says so and shows the nearest traced one. Saves a screenshot, DIR/step-page.png, and prints
its path. Exit status 0: passed, 1: failed.
"""

import argparse
import base64
import json
import math
import pathlib
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request

# WebDriver's names (https://www.w3.org/TR/webdriver2/).
ELEMENT = "element-6066-11e4-a52e-4f735466cecf"
ARROW_LEFT, ARROW_RIGHT = "\ue012", "\ue014"
RULE = "=" * 80  # printWalk's rule above and below each screen's title


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


class WebDriver:
    """A chromedriver process and one browser session."""

    def __init__(self, chromedriver, chromium, work):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        self.url = f"http://127.0.0.1:{port}"
        self.log = open(work / "chromedriver.log", "w")
        self.process = subprocess.Popen([chromedriver, f"--port={port}"], stdout=self.log,
                                        stderr=subprocess.STDOUT)
        self.session = None
        deadline = time.monotonic() + 30
        while True:
            try:
                if self.request("GET", "/status")["ready"]:
                    break
            except (urllib.error.URLError, ConnectionError):
                pass
            check(time.monotonic() < deadline, f"chromedriver did not start (see {self.log.name})")
            time.sleep(0.1)
        profile = work / "chromium-profile"  # fresh each run: no state from a previous one
        shutil.rmtree(profile, ignore_errors=True)
        options = {"binary": str(chromium),
                   "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                            f"--user-data-dir={profile}", "--window-size=1600,1200"]}
        answer = self.request("POST", "/session", {"capabilities": {"alwaysMatch": {
            "browserName": "chrome", "goog:chromeOptions": options}}})
        self.session = f"/session/{answer['sessionId']}"

    def request(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.url + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=60) as response:
                return json.load(response)["value"]
        except urllib.error.HTTPError as error:
            raise Failure(f"WebDriver {method} {path}: {error.read().decode(errors='replace')}") from None

    def command(self, method, path, body=None):
        return self.request(method, self.session + path, body)

    def find(self, css):
        return self.command("POST", "/element", {"using": "css selector", "value": css})[ELEMENT]

    def text(self, css):
        return self.command("GET", f"/element/{self.find(css)}/text")

    def rect(self, css):
        return self.command("GET", f"/element/{self.find(css)}/rect")

    def displayed(self, css):
        return self.command("GET", f"/element/{self.find(css)}/displayed")

    def click(self, css):
        self.command("POST", f"/element/{self.find(css)}/click", {})

    def press(self, key):
        self.command("POST", "/actions", {"actions": [{"type": "key", "id": "keyboard", "actions": [
            {"type": "keyDown", "value": key}, {"type": "keyUp", "value": key}]}]})

    def click_at(self, css, x, y):
        """A mouse click at (x, y) CSS pixels from the element's centre."""
        self.command("POST", "/actions", {"actions": [{"type": "pointer", "id": "mouse",
            "parameters": {"pointerType": "mouse"}, "actions": [
                {"type": "pointerMove", "duration": 0, "x": x, "y": y,
                 "origin": {ELEMENT: self.find(css)}},
                {"type": "pointerDown", "button": 0}, {"type": "pointerUp", "button": 0}]}]})
        self.command("DELETE", "/actions")

    def close(self):
        try:
            if self.session:
                self.request("DELETE", self.session)
        finally:
            self.process.terminate()
            self.process.wait(timeout=30)
            self.log.close()


def run(command):
    print("+", " ".join(map(str, command)), flush=True)
    result = subprocess.run(command, capture_output=True, text=True)
    check(result.returncode == 0,
          f"{command[0]} exited with {result.returncode}:\n{result.stderr}{result.stdout[-2000:]}")
    return result.stdout


def read_trace(page):
    script = (page / "trace-data.js").read_text(encoding="utf-8")
    assignment = "window.facetStepTrace = "
    begin = script.index(assignment) + len(assignment)
    return json.loads(script[begin:script.rindex(";")])


def words(text):
    """The text without printWalk's rules, as a list of words: spacing and line breaks set aside, every
    word and number kept."""
    return " ".join(line for line in text.splitlines() if line != RULE).split()


def first_difference(expected, shown):
    for n, (a, b) in enumerate(zip(expected, shown)):
        if a != b:
            return (f"word {n}: printed {a!r}, page shows {b!r}\n  printed: {' '.join(expected[max(0, n - 8):n + 8])}"
                    f"\n  page:    {' '.join(shown[max(0, n - 8):n + 8])}")
    return f"printed {len(expected)} words, page shows {len(shown)}"


def wait_for_text(driver, css, wanted, what):
    deadline = time.monotonic() + 10
    while (shown := driver.text(css)) != wanted and time.monotonic() < deadline:
        time.sleep(0.05)
    check(shown == wanted, f"{what}: {css} shows {shown!r}, expected {wanted!r}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--facet", required=True, type=pathlib.Path)
    parser.add_argument("--work", required=True, type=pathlib.Path)
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("--chromedriver", default=shutil.which("chromedriver") or "chromedriver")
    parser.add_argument("step_arguments", nargs=argparse.REMAINDER, help="MODEL and options of facet step")
    args = parser.parse_args()
    work = args.work.resolve()
    page = work / "page"
    shutil.rmtree(page, ignore_errors=True)
    work.mkdir(parents=True, exist_ok=True)
    step = [str(args.facet), "step", *args.step_arguments]

    run(step + ["--html", str(page)])
    trace = read_trace(page)
    width, height, stages, walks = trace["width"], trace["height"], trace["stages"], trace["walks"]
    check(len(stages) >= 2, f"the page has {len(stages)} stage(s); stepping needs two")
    # The traced pixel nearest the centre that a triangle covers: the longest history.
    covered = [w for w in walks if w[2] is not None]
    check(covered, "no traced pixel is covered by a triangle")
    x, y = min(((w[0], w[1]) for w in covered),
               key=lambda p: (p[0] - width / 2) ** 2 + (p[1] - height / 2) ** 2)
    printed = run(step + ["--pixel", f"{x},{y}", "--print"])

    driver = WebDriver(args.chromedriver, args.chromium, work)
    try:
        driver.command("POST", "/url", {"url": (page / "index.html").as_uri()})
        check(not driver.displayed("#data-error"), "the page could not read trace-data.js")
        titles = [s["title"] for s in stages]
        wait_for_text(driver, "#stage-title", titles[0], "at load")

        # Stepping: the buttons, then each key, forward and back.
        driver.click("#next")
        wait_for_text(driver, "#stage-title", titles[1], "after Next")
        driver.click("#prev")
        wait_for_text(driver, "#stage-title", titles[0], "after Previous")
        for forward, back in ((ARROW_RIGHT, ARROW_LEFT), ("n", "b")):
            driver.press(forward)
            wait_for_text(driver, "#stage-title", titles[1], f"after the key {forward!r}")
            driver.press(back)
            wait_for_text(driver, "#stage-title", titles[0], f"after the key {back!r}")
        final = next((s["title"] for s in stages if s["id"] == "final"), titles[-1])
        driver.press("0")
        wait_for_text(driver, "#stage-title", final, "after the key 0 (the final image)")
        driver.press("1")
        wait_for_text(driver, "#stage-title", titles[0], "after the key 1")

        # A click on the centre of the image's pixel (x, y), as the browser has scaled the image.
        box = driver.rect("#stage-image")
        scale_x, scale_y = box["width"] / width, box["height"] / height
        check(scale_x >= 2 and scale_y >= 2, f"the image is drawn at {scale_x:.2f}× only: too small to aim")

        def click_pixel(px, py):
            """A click on the last whole CSS pixel inside image pixel (px, py), at its lower right: rounding
            instead of truncating the position would land on the next pixel. WebDriver clicks at whole CSS
            pixels, measured from the element's centre rounded down."""
            centre_x = math.floor(box["x"] + box["width"] / 2)
            centre_y = math.floor(box["y"] + box["height"] / 2)
            target_x = math.ceil(box["x"] + (px + 1) * scale_x) - 1
            target_y = math.ceil(box["y"] + (py + 1) * scale_y) - 1
            driver.click_at("#stage-image", target_x - centre_x, target_y - centre_y)

        click_pixel(x, y)
        wait_for_text(driver, "#pixel", f"{x},{y}", f"after a click on the traced pixel ({x}, {y})")
        check(not driver.displayed("#notice"), f"a notice for the traced pixel: {driver.text('#notice')!r}")
        expected, shown = words(printed), words(driver.text("#history"))
        check(shown == expected, "#history differs from facet step --print: " + first_difference(expected, shown))
        marker = driver.rect("#marker")
        centre = (marker["x"] + marker["width"] / 2 - box["x"], marker["y"] + marker["height"] / 2 - box["y"])
        check(abs(centre[0] - (x + 0.5) * scale_x) <= 1 and abs(centre[1] - (y + 0.5) * scale_y) <= 1,
              f"the marker's centre is at {centre}, not on pixel ({x}, {y})")
        driver.press("0")  # the final image, with the pixel marked and its history beside it
        wait_for_text(driver, "#stage-title", final, "after the key 0")
        screenshot = work / "step-page.png"
        screenshot.write_bytes(base64.b64decode(driver.command("GET", "/screenshot")))
        print(f"screenshot: {screenshot}")

        # A pixel next to it that was not traced: the nearest traced one (first in trace order on a tie).
        traced = {(w[0], w[1]) for w in walks}
        untraced = [(px, py) for px, py in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1))
                    if 0 <= px < width and 0 <= py < height and (px, py) not in traced]
        if untraced:
            ux, uy = untraced[0]
            nearest = min(walks, key=lambda w: (w[0] - ux) ** 2 + (w[1] - uy) ** 2)
            click_pixel(ux, uy)
            wait_for_text(driver, "#pixel", f"{nearest[0]},{nearest[1]}", f"after a click on ({ux}, {uy})")
            wait_for_text(driver, "#notice",
                          f"pixel ({ux}, {uy}) is not traced; showing the nearest traced pixel "
                          f"({nearest[0]}, {nearest[1]}); trace it with facet step --pixel {ux},{uy}",
                          "the notice for an untraced pixel")
        else:
            print("every pixel is traced: no untraced pixel to click")
    finally:
        driver.close()
    print("passed")


if __name__ == "__main__":
    try:
        main()
    except Failure as failure:
        print(f"FAILED: {failure}", file=sys.stderr)
        sys.exit(1)
