#!/usr/bin/env python3
"""The web page of `facet step --html` in a real browser: Debian's Chromium, headless, driven through
chromedriver by WebDriver over HTTP (python3's standard library only).

    browser_test.py --facet FACET --work DIR [--chromium PATH] [--chromedriver PATH] MODEL [OPTION...]

Twice, in a window of 1280x720 (a projector) with `facet step MODEL OPTION... --html DIR/page` (every
pixel traced for a small image) and in one of 1920x1080 with --html-step 5 and a region traced in full
added: opens DIR/page/index.html; checks that the whole image is in view without scrolling and at least
half the window high; steps through the stages with the buttons and the keys (the key of every stage,
up to the last) and checks the stage title follows; clicks a traced pixel of the image and checks that
the page shows that pixel and, word for word and number for number, the history that
`facet step MODEL OPTION... --pixel X,Y --print` prints; zooms in with the keys, clicks another pixel at
the corners of its enlarged square and checks its history the same way, and in a screenshot that the
square under the click shows that pixel's colour of the final image and is ringed by the marker; then
clicks a pixel that was not traced and checks that the page says so and shows the nearest traced one.
Saves the screenshots, DIR/step-page-WxH.png, and prints their paths. Exit status 0: passed, 1: failed.
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
import zlib

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
                            f"--user-data-dir={profile}", "--window-size=2560,1600",
                            "--force-device-scale-factor=1", "--hide-scrollbars"]}
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

    def script(self, code, *args):
        return self.command("POST", "/execute/sync", {"script": code, "args": list(args)})

    def click(self, css):
        self.command("POST", f"/element/{self.find(css)}/click", {})

    def press(self, key):
        self.command("POST", "/actions", {"actions": [{"type": "key", "id": "keyboard", "actions": [
            {"type": "keyDown", "value": key}, {"type": "keyUp", "value": key}]}]})

    def click_at(self, x, y):
        """A mouse click at (x, y), whole CSS pixels from the viewport's top left."""
        self.command("POST", "/actions", {"actions": [{"type": "pointer", "id": "mouse",
            "parameters": {"pointerType": "mouse"}, "actions": [
                {"type": "pointerMove", "duration": 0, "x": x, "y": y, "origin": "viewport"},
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


def script_object(path, marker, end):
    text = path.read_text(encoding="utf-8")
    begin = text.index(marker) + len(marker)
    return json.loads(text[begin:text.rindex(end)])


def read_page(page):
    """The index (trace-data.js) and every walk of the tiles, each as (x, y, triangle, heading text,
    [(id, title, text)]), as the page's script rebuilds them."""
    index = script_object(page / "trace-data.js", "window.facetStepTrace = ", ";")
    walks = []
    for column, row in index["tiles"]:
        tile = script_object(page / "trace-tiles" / f"tile-{column}-{row}.js",
                             f'facetStepTile("{column},{row}", ', ")")
        lines, screens = index["lines"] + tile["lines"], index["screens"] + tile["screens"]

        def screen(n):
            id_, title, text = screens[n]
            return lines[id_], lines[title], "\n".join(lines[k] for k in text)

        for x, y, triangle, heading, numbers in tile["walks"]:
            walks.append((x, y, triangle, screen(heading)[2], [screen(n) for n in numbers]))
    return index, walks


def read_png(data):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit, non-interlaced RGB or RGBA PNG."""
    check(data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG")
    at, idat = 8, b""
    while at < len(data):
        length = int.from_bytes(data[at:at + 4], "big")
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height = int.from_bytes(body[0:4], "big"), int.from_bytes(body[4:8], "big")
            depth, colour, interlace = body[8], body[9], body[12]
            check(depth == 8 and colour in (2, 6) and interlace == 0, f"a PNG of depth {depth}, type {colour}")
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    channels = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):  # the five filters of the PNG specification, section 9
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1: line[i] = (line[i] + a) & 255
            elif kind == 2: line[i] = (line[i] + b) & 255
            elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[i:i + 3]) for i in range(0, stride, channels)])
        previous = line
    return width, height, rows


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


STAGE_KEYS = "123456789acdeghijklmopqrstuvwxyz"  # the page's key for each stage, in order
# The projector's window with every pixel traced, and a large screen's with a sparse grid and a region.
RUNS = (((1280, 720), []), ((1920, 1080), ["--html-step", "5", "--html-region", "10,10,20,15"]))


def canvas_data(driver, name):
    return float(driver.script("return document.getElementById('stage-view').dataset[arguments[0]];", name))


def image_box(driver, width, height):
    """Where the page draws the image, in CSS pixels of the window, from the canvas's place and the view
    the page says it draws (the screenshot checks that the drawing agrees)."""
    canvas = driver.rect("#stage-view")
    scale = canvas_data(driver, "scale")
    return {"x": canvas["x"] + canvas_data(driver, "left"), "y": canvas["y"] + canvas_data(driver, "top"),
            "width": width * scale, "height": height * scale, "scale": scale, "canvas": canvas}


def click_pixel(driver, box, px, py, corner):
    """A click on the first (corner "upper left") or last ("lower right") whole CSS pixel inside image
    pixel (px, py): rounding instead of truncating the position would land on the next pixel. WebDriver
    clicks at whole CSS pixels of the viewport (the page does not scroll)."""
    if corner == "upper left":
        target_x = math.ceil(box["x"] + px * box["scale"])
        target_y = math.ceil(box["y"] + py * box["scale"])
    else:
        target_x = math.ceil(box["x"] + (px + 1) * box["scale"]) - 1
        target_y = math.ceil(box["y"] + (py + 1) * box["scale"]) - 1
    driver.click_at(target_x, target_y)


def check_history(driver, printed, what):
    expected, shown = words(printed), words(driver.text("#history"))
    check(shown == expected, f"{what}: #history differs from facet step --print: " + first_difference(expected, shown))


def check_page(driver, step, work, size, extra):
    window_width, window_height = size
    page = work / f"page-{window_width}x{window_height}"
    shutil.rmtree(page, ignore_errors=True)
    run(step + extra + ["--html", str(page)])  # the page's options; --print traces the same pixels without them
    index, walks = read_page(page)
    width, height, stages = index["width"], index["height"], index["stages"]
    check(len(stages) >= 2, f"the page has {len(stages)} stage(s); stepping needs two")
    traced = {(w[0], w[1]) for w in walks}
    if not extra:
        check(traced == {(x, y) for x in range(width) for y in range(height)},
              f"{len(traced)} pixels traced of the {width}x{height} image; every pixel expected")
    # The traced pixel nearest the centre that a triangle covers, other than the one shown at first (so
    # that the click changes the pixel shown): a long history.
    opening = tuple(index["opening"][:2])
    covered = [w for w in walks if w[2] is not None and (w[0], w[1]) != opening]
    check(covered, "no traced pixel is covered by a triangle")
    x, y = min(((w[0], w[1]) for w in covered),
               key=lambda p: ((p[0] - width / 2) ** 2 + (p[1] - height / 2) ** 2, p[1], p[0]))
    printed = run(step + ["--pixel", f"{x},{y}", "--print"])

    # The window's inside (the viewport) at the size asked: headless, the window has no frame, and the
    # viewport follows a resize a moment later.
    deadline = time.monotonic() + 10
    rect = [window_width, window_height]
    while True:
        driver.command("POST", "/window/rect", {"width": rect[0], "height": rect[1]})
        time.sleep(0.2)
        inner = driver.script("return [window.innerWidth, window.innerHeight];")
        if inner == [window_width, window_height] or time.monotonic() > deadline:
            break
        rect = [rect[0] + window_width - inner[0], rect[1] + window_height - inner[1]]
    check(inner == [window_width, window_height], f"the viewport is {inner}, not {size}")
    driver.command("POST", "/url", {"url": (page / "index.html").as_uri()})
    check(not driver.displayed("#data-error"), "the page could not read trace-data.js")
    titles = [s["title"] for s in stages]
    wait_for_text(driver, "#stage-title", titles[0], "at load")
    wait_for_text(driver, "#pixel", f"{opening[0]},{opening[1]}", "at load")

    # In view without scrolling, and large.
    check(driver.script("return document.documentElement.scrollHeight <= window.innerHeight + 1 && "
                        "document.documentElement.scrollWidth <= window.innerWidth + 1;"),
          f"the page scrolls at {size}")
    box = image_box(driver, width, height)
    check(box["x"] >= -1 and box["y"] >= -1 and box["x"] + box["width"] <= window_width + 1 and
          box["y"] + box["height"] <= window_height + 1, f"the image at {box} is not all in the {size} window")
    check(box["height"] >= window_height / 2, f"the image is {box['height']:.0f} pixels high in a window of "
          f"{window_height}: less than half")
    check(box["scale"] >= 2, f"the image is drawn at {box['scale']:.2f}× only: too small to aim")

    # Stepping: the buttons, then each key, forward and back; the key of every stage, shown beside it.
    driver.click("#next")
    wait_for_text(driver, "#stage-title", titles[1], "after Next")
    driver.click("#prev")
    wait_for_text(driver, "#stage-title", titles[0], "after Previous")
    for forward, back in ((ARROW_RIGHT, ARROW_LEFT), ("n", "b"), ("]", "[")):
        driver.press(forward)
        wait_for_text(driver, "#stage-title", titles[1], f"after the key {forward!r}")
        driver.press(back)
        wait_for_text(driver, "#stage-title", titles[0], f"after the key {back!r}")
    check(len(stages) <= len(STAGE_KEYS), f"{len(stages)} stages: more than the {len(STAGE_KEYS)} keys")
    for n, key in enumerate(STAGE_KEYS[:len(stages)]):
        driver.press(key)
        wait_for_text(driver, "#stage-counter", f"{n + 1} of {len(stages)}", f"after the key {key!r}")
        wait_for_text(driver, "#stage-title", titles[n], f"after the key {key!r}")
        wait_for_text(driver, f"#stage-list li:nth-child({n + 1}) kbd", key, f"the key shown for stage {n + 1}")
    final = next((s["title"] for s in stages if s["id"] == "final"), titles[-1])
    driver.press("0")
    wait_for_text(driver, "#stage-title", final, "after the key 0 (the final image)")
    driver.press("1")
    wait_for_text(driver, "#stage-title", titles[0], "after the key 1")

    # A click on pixel (x, y) as the page fits the image.
    click_pixel(driver, box, x, y, "lower right")
    wait_for_text(driver, "#pixel", f"{x},{y}", f"after a click on the traced pixel ({x}, {y})")
    check(not driver.displayed("#notice"), f"a notice for the traced pixel: {driver.text('#notice')!r}")
    check_history(driver, printed, f"pixel ({x}, {y})")

    # Zoomed in four times about the marked pixel: another traced pixel near it, clicked at both corners
    # of its square.
    driver.press("0")  # the final image, whose colours the screenshot is checked against
    wait_for_text(driver, "#stage-title", final, "after the key 0")
    fitted = box["scale"]
    driver.press("+")
    driver.click("#zoom-in")
    box = image_box(driver, width, height)
    check(abs(box["scale"] - 4 * fitted) < 1e-6, f"zoomed twice from {fitted}: {box['scale']}, not 4 times")
    canvas = box["canvas"]

    def in_view(p):
        return (box["x"] + p[0] * box["scale"] >= canvas["x"] + 6 and box["y"] + p[1] * box["scale"] >= canvas["y"] + 6
                and box["x"] + (p[0] + 1) * box["scale"] <= canvas["x"] + canvas["width"] - 6
                and box["y"] + (p[1] + 1) * box["scale"] <= canvas["y"] + canvas["height"] - 6)

    walk_at = {(w[0], w[1]): w for w in reversed(walks)}  # the first walk at each pixel

    def clear_of_outline(p):
        """Whether the pixel's traced triangle's outline (drawn over the image) passes farther than 0.75
        pixels from its centre, leaving the middle of its square to compare colours."""
        triangle = walk_at[p][2]
        cx, cy = p[0] + 0.5, p[1] + 0.5
        for piece in index["outlines"].get(str(triangle), []) if triangle is not None else []:
            for (ax, ay), (bx, by) in zip(piece, piece[1:] + piece[:1]):
                length2 = (bx - ax) ** 2 + (by - ay) ** 2
                t = 0 if length2 == 0 else max(0, min(1, ((cx - ax) * (bx - ax) + (cy - ay) * (by - ay)) / length2))
                if (ax + t * (bx - ax) - cx) ** 2 + (ay + t * (by - ay) - cy) ** 2 < 0.75 ** 2:
                    return False
        return True

    near = [p for p in traced if p != (x, y) and in_view(p) and clear_of_outline(p)]
    check(near, "no other traced pixel in view after zooming in")
    x2, y2 = min(near, key=lambda p: ((p[0] - x - 2) ** 2 + (p[1] - y - 1) ** 2, p[1], p[0]))
    printed2 = run(step + ["--pixel", f"{x2},{y2}", "--print"])
    for corner in ("upper left", "lower right"):
        click_pixel(driver, box, x, y, corner)  # away and back: each click must change the pixel shown
        wait_for_text(driver, "#pixel", f"{x},{y}", f"zoomed in, after a click at the {corner} of ({x}, {y})")
        click_pixel(driver, box, x2, y2, corner)
        wait_for_text(driver, "#pixel", f"{x2},{y2}", f"zoomed in, after a click at the {corner} of ({x2}, {y2})")
    check_history(driver, printed2, f"zoomed in, pixel ({x2}, {y2})")

    # The screenshot: under the click, the square shows pixel (x2, y2) of the final image, ringed.
    shot = base64.b64decode(driver.command("GET", "/screenshot"))
    screenshot = work / f"step-page-{window_width}x{window_height}.png"
    screenshot.write_bytes(shot)
    print(f"screenshot: {screenshot}")
    shot_width, _, shot_rows = read_png(shot)
    check(shot_width == window_width, f"the screenshot is {shot_width} pixels wide, not {window_width}")
    final_file = next(s["file"] for s in stages if s["title"] == final)
    _, _, final_rows = read_png((page / final_file).read_bytes())
    wanted = final_rows[y2][x2]
    left, top, cell = box["x"] + x2 * box["scale"], box["y"] + y2 * box["scale"], box["scale"]
    samples = [shot_rows[math.floor(top + cell * (0.3 + 0.1 * j))][math.floor(left + cell * (0.3 + 0.1 * i))]
               for i in range(5) for j in range(5)]
    matching = sum(all(abs(a - b) <= 3 for a, b in zip(colour, wanted)) for colour in samples)
    check(matching >= 13, f"the square of ({x2}, {y2}) shows {sorted(set(samples))}, not its colour {wanted}")
    ring = shot_rows[math.floor(top + cell / 2)][math.floor(left) - 3]
    check(ring[0] >= 230 and 200 <= ring[1] <= 240 and ring[2] <= 30, f"no marker left of ({x2}, {y2}): {ring}")

    # Fitted again: a pixel that was not traced shows the nearest traced one (grid first on a tie, then the
    # region, then the pixel traced first); a pixel of the region is traced.
    driver.press("f")
    box = image_box(driver, width, height)
    check(abs(box["scale"] - fitted) < 1e-6, f"the key f gives {box['scale']}, not the fitted {fitted}")
    step_n, region = index["gridStep"], index["region"]

    def order(p):
        on_grid = (p[0] - step_n // 2) % step_n == 0 and (p[1] - step_n // 2) % step_n == 0
        in_region = region is not None and region[0] <= p[0] < region[0] + region[2] and \
            region[1] <= p[1] < region[1] + region[3]
        return 0 if on_grid else 1 if in_region else 2

    untraced = [(px, py) for px, py in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1))
                if 0 <= px < width and 0 <= py < height and (px, py) not in traced]
    if untraced:
        ux, uy = untraced[0]
        nearest = min(traced, key=lambda p: ((p[0] - ux) ** 2 + (p[1] - uy) ** 2, order(p), p[1], p[0]))
        click_pixel(driver, box, ux, uy, "lower right")
        wait_for_text(driver, "#pixel", f"{nearest[0]},{nearest[1]}", f"after a click on ({ux}, {uy})")
        wait_for_text(driver, "#notice",
                      f"pixel ({ux}, {uy}) is not traced; showing the nearest traced pixel "
                      f"({nearest[0]}, {nearest[1]}); trace it with facet step --pixel {ux},{uy}",
                      "the notice for an untraced pixel")
    else:
        print("every pixel is traced: no untraced pixel to click")
    if region is not None:
        rx, ry = region[0] + 1, region[1] + 1
        check((rx, ry) in traced and (rx - step_n // 2) % step_n != 0, f"({rx}, {ry}) of the region is not traced")
        click_pixel(driver, box, rx, ry, "upper left")
        wait_for_text(driver, "#pixel", f"{rx},{ry}", f"after a click on ({rx}, {ry}) of the region")
        check(not driver.displayed("#notice"), f"a notice for the region's pixel: {driver.text('#notice')!r}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--facet", required=True, type=pathlib.Path)
    parser.add_argument("--work", required=True, type=pathlib.Path)
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("--chromedriver", default=shutil.which("chromedriver") or "chromedriver")
    parser.add_argument("step_arguments", nargs=argparse.REMAINDER, help="MODEL and options of facet step")
    args = parser.parse_args()
    work = args.work.resolve()
    work.mkdir(parents=True, exist_ok=True)
    step = [str(args.facet), "step", *args.step_arguments]
    driver = WebDriver(args.chromedriver, args.chromium, work)
    try:
        for size, extra in RUNS:
            print(f"window {size[0]}x{size[1]}", flush=True)
            check_page(driver, step, work, size, extra)
    finally:
        driver.close()
    print("passed")


if __name__ == "__main__":
    try:
        main()
    except Failure as failure:
        print(f"FAILED: {failure}", file=sys.stderr)
        sys.exit(1)
