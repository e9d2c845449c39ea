#include "step/html_page.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "io/text_file.h"
#include "step/notation.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The page itself: the same for every trace, which it reads from trace-data.js. Vanilla HTML, CSS and
// script, nothing from the network, so it works from a USB stick in a lecture hall.
constexpr std::string_view kIndexHtml = R"html(<!DOCTYPE html>
<!--
  facet step --html: one pixel's way through the pipeline, beside images of the whole frame after each
  stage. Open this file in a browser; it needs nothing from the network.

  Files: index.html (this page, the same for every trace), trace-data.js (the index of the trace, a script
  that sets the global facetStepTrace, since a page opened from file:// cannot fetch JSON), the stage
  images, and trace-tiles/tile-C-R.js: the walks of the traced pixels of one tile (tileSize × tileSize
  pixels, column C and row R of tiles), a script calling facetStepTile("C,R", tile). The page loads a tile
  with a script tag when a pixel of it is clicked.

  trace-data.js holds one object:
    width, height       the frame's size in pixels
    title, commandLine  the heading, and the facet step command that made the page
    gridStep            pixels traced every gridStep in x and y, from floor(gridStep/2) (1: every pixel)
    region              null, or [x, y, width, height]: pixels also traced, all of them
    tileSize, tiles     the tiles' size in pixels, and [column, row] of each tile written
    opening             [x, y, n]: the walk shown when the page opens, the n-th of its tile
    stages              [{id, title, file, description}], pipeline order; id "final" is the finished frame
    outlines            {triangle number: [[[x, y] × 3] per piece]}: the traced triangle after clipping,
                        in window coordinates (pixels, y down), as the rasterizer met it
    lines               the lines of text more than one tile uses, numbered from 0
    screens             the screens more than one tile uses: [id, title, [text lines]], line numbers
  A tile holds { lines, screens, walks }: its own lines and screens, numbered after the index's, and one
  walk per traced pixel: [x, y, triangle (null: none), heading, [screens]]; the heading is a screen whose
  text is the lines facet step --print writes above the screens (the pixel, its triangle, the verdict). A
  text is its lines joined with "\n".
  Size, every pixel traced: spot_triangulated.obj at 160x120 (19200 walks), an index of 0.4 MB and 14 MB
  of tiles (one file of all the text, numbered per screen, took 32 MB); at 320x240 (76800 walks), 1.5 MB
  and 48 MB in 80 tiles of at most 4.2 MB. shadows.json (about 9000 triangles in three draws, shadows
  traced with rays) at 320x240: 7.9 MB and 149 MB, tiles of at most 5.6 MB. A click loads one tile.
    notation            [[symbol, meaning, where]]: the symbols the screens print, for the legend
-->
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>facet step</title>
<style>
  :root { --bg: #ffffff; --fg: #000000; --muted: #303030; --panel: #eeeeee; --accent: #0033aa;
          --screen-font: clamp(12px, 1vw, 26px); }
  html.dark { --bg: #000000; --fg: #ffffff; --muted: #dddddd; --panel: #1c1c1c; --accent: #99ccff; }
  html, body { margin: 0; height: 100%; background: var(--bg); color: var(--fg); }
  /* The window is the page: the image and the history each fill their part, nothing below the fold. */
  body { font: clamp(15px, 1.2vw, 24px)/1.35 sans-serif; display: flex; flex-direction: column;
         height: 100vh; overflow: hidden; }
  header { flex: none; display: flex; align-items: baseline; gap: 1em; padding: 0.3em 0.8em;
           border-bottom: 2px solid var(--fg); }
  header h1 { font-size: 1.2em; margin: 0; white-space: nowrap; }
  #command-line { font: 0.8em monospace; color: var(--muted); flex: 1 1 0; min-width: 0;
                  white-space: nowrap; overflow: hidden; text-overflow: ellipsis; }
  button { font: inherit; color: var(--fg); background: var(--panel); border: 2px solid var(--fg);
           border-radius: 4px; padding: 0 0.5em; cursor: pointer; }
  button:disabled { opacity: 0.4; cursor: default; }
  kbd { font: 0.85em monospace; border: 1px solid var(--muted); border-radius: 3px; padding: 0 0.2em; }
  main { flex: 1 1 auto; min-height: 0; display: flex; gap: 0.6em; padding: 0.4em 0.6em; }
  #stage-panel { flex: 1 1 0; min-width: 12em; display: flex; flex-direction: column; gap: 0.3em; }
  .toolbar { flex: none; display: flex; align-items: center; gap: 0.5em; min-width: 0; }
  #stage-counter { white-space: nowrap; }
  #stage-title { font-size: 1.1em; margin: 0; flex: 1 1 0; min-width: 0; white-space: nowrap;
                 overflow: hidden; text-overflow: ellipsis; }
  /* The image drawn on a canvas, pixels as sharp squares at any zoom. */
  #viewer { flex: 1 1 auto; min-height: 8em; position: relative; border: 2px solid var(--fg); }
  #stage-view { position: absolute; inset: 0; width: 100%; height: 100%; background: var(--panel);
                cursor: crosshair; touch-action: none; }
  #zoom-level { min-width: 4em; text-align: center; }
  .hint { color: var(--muted); font-size: 0.8em; }
  #key-hint { flex: 1 1 0; min-width: 0; }
  /* The history: 80 columns (a screen's width), scrolling on its own beside the image. */
  #side-panel { flex: none; width: calc(48 * var(--screen-font) + 2.5em); max-width: 60vw;
                overflow-y: auto; padding-right: 0.3em; }
  h2 { font-size: 1.1em; margin: 0.3em 0; }
  #stage-description { color: var(--muted); margin: 0 0 0.3em 0; font-size: 0.9em; }
  details summary { cursor: pointer; }
  .entries { list-style: none; padding: 0; margin: 0.2em 0; display: grid; gap: 0.15em 0.5em;
             grid-template-columns: repeat(auto-fill, minmax(12em, 1fr)); font-size: 0.8em; }
  /* One line per entry: a long title ends in an ellipsis, the whole of it in the tooltip. */
  .entries li { min-width: 0; }
  .entries button, .entries a { display: block; width: 100%; box-sizing: border-box; text-align: left;
                                white-space: nowrap; overflow: hidden; text-overflow: ellipsis; }
  #stage-list button[aria-current="true"] { background: var(--fg); color: var(--bg); }
  #stage-list button[aria-current="true"] kbd { border-color: var(--bg); }
  #screen-list a { color: var(--accent); }
  #notice { border: 2px solid var(--fg); background: var(--panel); padding: 0.3em 0.5em; }
  #history #verdict { background: none; padding: 0; font-weight: bold; margin: 0.4em 0; white-space: pre-wrap; }
  #history section { border-top: 2px solid var(--fg); margin-top: 0.8em; }
  #history h3 { font-size: 1em; margin: 0.3em 0; }
  #history pre { font: var(--screen-font)/1.35 monospace; max-width: 100%; margin: 0; padding: 0.4em;
                 background: var(--panel); overflow-x: auto; }
  #data-error, #load-error { margin: 1em; font-weight: bold; }
  #notation { margin: 0 1em 1em; }
  #notation summary { cursor: pointer; font-weight: bold; }
  #notation td { padding: 0.1em 0.6em; vertical-align: top; }
  #notation td:first-child { font-family: monospace; white-space: nowrap; }
  #notation td:last-child { color: var(--muted); }
</style>
</head>
<body>
<header>
  <h1 id="page-title">facet step</h1>
  <code id="command-line"></code>
  <button id="theme" type="button" title="Switch between dark text on white and white text on black">Dark</button>
</header>
<noscript><p id="load-error">This page needs JavaScript (it runs offline and loads nothing from the network).</p></noscript>
<p id="data-error" hidden>trace-data.js is missing or broken: the page shows the trace facet step wrote beside it, in the same folder.</p>
<main>
  <section id="stage-panel">
    <div id="stage-nav" class="toolbar">
      <button id="prev" type="button" title="Previous stage (left arrow, b or [)">&larr;</button>
      <span id="stage-counter"></span>
      <button id="next" type="button" title="Next stage (right arrow, n or ])">&rarr;</button>
      <h2 id="stage-title"></h2>
    </div>
    <div id="viewer"><canvas id="stage-view"></canvas></div>
    <div id="zoom-bar" class="toolbar">
      <button id="zoom-out" type="button" title="Zoom out (key -)">&minus;</button>
      <span id="zoom-level"></span>
      <button id="zoom-in" type="button" title="Zoom in (key +)">+</button>
      <button id="zoom-fit" type="button" title="The whole image (key f)">Fit</button>
      <span id="key-hint" class="hint">Click a pixel for its history; drag to move, wheel to zoom.
        Keys: <kbd>&larr;</kbd> <kbd>&rarr;</kbd> stages, the key beside each stage jumps to it,
        <kbd>0</kbd> final image, <kbd>+</kbd> <kbd>&minus;</kbd> <kbd>f</kbd> zoom, <kbd>?</kbd> notation.</span>
    </div>
  </section>
  <section id="side-panel">
    <p id="stage-description"></p>
    <details id="stages" open><summary>Stages and their keys</summary><ol id="stage-list" class="entries"></ol></details>
    <details id="notation" hidden>
      <summary>Notation: the symbols the screens print (key ?)</summary>
      <table><thead><tr><th>Symbol</th><th>Meaning</th><th>Screens</th></tr></thead>
        <tbody id="notation-rows"></tbody></table>
    </details>
    <section id="pixel-panel">
      <h2>Pixel <span id="pixel"></span> <span id="pixel-triangle"></span></h2>
      <p id="notice" hidden></p>
      <nav><ol id="screen-list" class="entries"></ol></nav>
      <div id="history"></div>
    </section>
  </section>
</main>
<script src="trace-data.js"></script>
<script>
"use strict";
(function () {
  const byId = (id) => document.getElementById(id);
  const trace = window.facetStepTrace;
  if (!trace || !trace.tiles || !trace.stages) {
    byId("data-error").hidden = false;
    return;
  }
  const canvas = byId("stage-view");
  const context = canvas.getContext("2d");
  const image = new Image();
  image.addEventListener("load", () => draw());
  // 1 to 9, then letters; b and n step, f fits the image.
  const stageKeys = "123456789acdeghijklmopqrstuvwxyz";
  const finalFound = trace.stages.findIndex((s) => s.id === "final");
  const finalStage = finalFound >= 0 ? finalFound : trace.stages.length - 1;
  let stage = 0;
  let shown = null;  // {walk, tile}: the walk shown, and the tile it came from

  // The tiles: loaded on demand with a script tag (which works from file://), kept once loaded.
  const sharedLines = trace.lines.length, sharedScreens = trace.screens.length;
  const tiles = new Map(), loading = new Map();
  window.facetStepTile = (key, tile) => { tiles.set(key, tile); };
  const tileKey = (x, y) => Math.floor(x / trace.tileSize) + "," + Math.floor(y / trace.tileSize);
  function loadTile(key) {
    if (tiles.has(key)) return Promise.resolve(tiles.get(key));
    if (!loading.has(key)) {
      loading.set(key, new Promise((resolve, reject) => {
        const script = document.createElement("script");
        script.src = "trace-tiles/tile-" + key.replace(",", "-") + ".js";
        script.onload = () => tiles.has(key) ? resolve(tiles.get(key)) : reject(new Error(script.src));
        script.onerror = () => { loading.delete(key); reject(new Error(script.src)); };
        document.head.append(script);
      }));
    }
    return loading.get(key);
  }
  const lineOf = (n, tile) => n < sharedLines ? trace.lines[n] : tile.lines[n - sharedLines];
  const screenOf = (n, tile) => n < sharedScreens ? trace.screens[n] : tile.screens[n - sharedScreens];
  const textOf = (lines, tile) => lines.map((n) => lineOf(n, tile)).join("\n");

  // Which pixels are traced: the grid (every gridStep-th from floor(gridStep/2)), the region, the opening.
  const step = trace.gridStep, gridStart = Math.floor(step / 2);
  const onGrid = (v, size) => v >= gridStart && v < size && (v - gridStart) % step === 0;
  const inRegion = (x, y) => trace.region !== null && x >= trace.region[0] && y >= trace.region[1] &&
      x < trace.region[0] + trace.region[2] && y < trace.region[1] + trace.region[3];
  const isOpening = (x, y) => trace.opening !== null && trace.opening[0] === x && trace.opening[1] === y;
  const isTraced = (x, y) => (onGrid(x, trace.width) && onGrid(y, trace.height)) || inRegion(x, y) || isOpening(x, y);
  // The grid position nearest v (the smaller on a tie), or null when the grid has none.
  function nearestOnGrid(v, size) {
    if (gridStart >= size) return null;
    const last = gridStart + Math.floor((size - 1 - gridStart) / step) * step;
    const below = Math.min(last, Math.max(gridStart, gridStart + Math.floor((v - gridStart) / step) * step));
    return below + step <= last && below + step - v < v - below ? below + step : below;
  }
  // The traced pixel nearest (x, y) in Euclidean distance; on a tie the grid's (the first in row order),
  // then the region's, then the opening pixel: the order facet step traces them.
  function nearestTraced(x, y) {
    const candidates = [];
    const gx = nearestOnGrid(x, trace.width), gy = nearestOnGrid(y, trace.height);
    if (gx !== null && gy !== null) candidates.push([gx, gy]);
    if (trace.region !== null) {
      const [rx, ry, rw, rh] = trace.region;
      candidates.push([Math.min(Math.max(x, rx), rx + rw - 1), Math.min(Math.max(y, ry), ry + rh - 1)]);
    }
    if (trace.opening !== null) candidates.push([trace.opening[0], trace.opening[1]]);
    let best = null, bestDistance = Infinity;
    for (const [cx, cy] of candidates) {
      const d = (cx - x) * (cx - x) + (cy - y) * (cy - y);
      if (d < bestDistance) { best = [cx, cy]; bestDistance = d; }
    }
    return best;
  }

  function fileUrl(file) { return file.split("/").map(encodeURIComponent).join("/"); }

  function rememberPlace() {
    const place = "#stage=" + (stage + 1) + (shown ? "&pixel=" + shown.walk[0] + "," + shown.walk[1] : "");
    try { history.replaceState(null, "", place); } catch (e) { /* some browsers refuse on file:// */ }
  }

  function showStage(n) {
    if (n < 0 || n >= trace.stages.length) return;
    stage = n;
    const s = trace.stages[n];
    image.src = fileUrl(s.file);
    canvas.setAttribute("aria-label", s.title);
    byId("stage-title").textContent = s.title;
    byId("stage-title").title = s.title;
    byId("stage-description").textContent = s.description;
    byId("stage-counter").textContent = (n + 1) + " of " + trace.stages.length;
    byId("prev").disabled = n === 0;
    byId("next").disabled = n === trace.stages.length - 1;
    byId("stage-list").querySelectorAll("button").forEach((button, k) => {
      button.setAttribute("aria-current", k === n ? "true" : "false");
    });
    rememberPlace();
  }

  // The view: image pixel (x, y) covers CSS pixels left + x·scale to left + (x + 1)·scale of the canvas
  // (and the same downwards); a click maps back by the same numbers.
  const view = {scale: 1, left: 0, top: 0, fitted: true};
  const viewSize = () => [canvas.clientWidth, canvas.clientHeight];
  const fitScale = () => Math.min(viewSize()[0] / trace.width, viewSize()[1] / trace.height);
  const largestScale = () => Math.max(64, fitScale());
  function settleView() {
    const [w, h] = viewSize();
    const ratio = window.devicePixelRatio || 1;
    const settle = (offset, extent, room) => {
      const placed = extent <= room ? (room - extent) / 2 : Math.min(0, Math.max(room - extent, offset));
      return Math.round(placed * ratio) / ratio;  // on a device pixel: cells and clicks agree
    };
    view.left = settle(view.left, trace.width * view.scale, w);
    view.top = settle(view.top, trace.height * view.scale, h);
  }
  function fit() {
    view.scale = fitScale();
    view.fitted = true;
    settleView();
    draw();
  }
  // Zoom to `scale`, keeping the image point under (ax, ay) (CSS pixels of the canvas) in place.
  function zoomAt(scale, ax, ay) {
    const to = Math.min(largestScale(), Math.max(fitScale(), scale));
    const px = (ax - view.left) / view.scale, py = (ay - view.top) / view.scale;
    view.scale = to;
    view.fitted = to === fitScale();
    view.left = ax - px * to;
    view.top = ay - py * to;
    settleView();
    draw();
  }
  // Keys and buttons zoom about the marked pixel when it is in view, else about the middle.
  function zoomBy(factor) {
    const [w, h] = viewSize();
    let ax = w / 2, ay = h / 2;
    if (shown) {
      const mx = view.left + (shown.walk[0] + 0.5) * view.scale, my = view.top + (shown.walk[1] + 0.5) * view.scale;
      if (mx >= 0 && my >= 0 && mx < w && my < h) { ax = mx; ay = my; }
    }
    zoomAt(view.scale * factor, ax, ay);
  }

  function draw() {
    const ratio = window.devicePixelRatio || 1;
    const [w, h] = viewSize();
    if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
      canvas.width = Math.round(w * ratio);
      canvas.height = Math.round(h * ratio);
    }
    context.setTransform(ratio, 0, 0, ratio, 0, 0);
    context.clearRect(0, 0, w, h);
    const s = view.scale;
    context.imageSmoothingEnabled = false;  // nearest neighbour: each pixel a square
    if (image.complete && image.naturalWidth > 0)
      context.drawImage(image, view.left, view.top, trace.width * s, trace.height * s);
    // The pixel grid, once a pixel is large enough for the lines not to hide it.
    if (s >= 8) {
      const x0 = Math.max(0, Math.floor(-view.left / s)), x1 = Math.min(trace.width, Math.ceil((w - view.left) / s));
      const y0 = Math.max(0, Math.floor(-view.top / s)), y1 = Math.min(trace.height, Math.ceil((h - view.top) / s));
      context.beginPath();
      for (let x = x0; x <= x1; ++x) {
        context.moveTo(view.left + x * s, view.top + y0 * s);
        context.lineTo(view.left + x * s, view.top + y1 * s);
      }
      for (let y = y0; y <= y1; ++y) {
        context.moveTo(view.left + x0 * s, view.top + y * s);
        context.lineTo(view.left + x1 * s, view.top + y * s);
      }
      context.lineWidth = 1;
      context.strokeStyle = "rgba(128, 128, 128, 0.7)";
      context.stroke();
    }
    if (shown) {
      // The traced triangle's edges as the rasterizer met them (each piece, after clipping).
      const triangle = shown.walk[2];
      const pieces = triangle === null ? [] : trace.outlines[String(triangle)] || [];
      context.beginPath();
      for (const piece of pieces) {
        piece.forEach(([x, y], k) => {
          const sx = view.left + x * s, sy = view.top + y * s;
          if (k === 0) context.moveTo(sx, sy); else context.lineTo(sx, sy);
        });
        context.closePath();
      }
      context.lineJoin = "round";
      context.lineWidth = 4;
      context.strokeStyle = "#000000";
      context.stroke();
      context.lineWidth = 2;
      context.strokeStyle = "#00ffff";
      context.stroke();
      // The pixel: a ring just outside its square, at least 14 CSS pixels across.
      const size = Math.max(s, 8);
      const cx = view.left + (shown.walk[0] + 0.5) * s, cy = view.top + (shown.walk[1] + 0.5) * s;
      context.lineWidth = 5;
      context.strokeStyle = "#000000";
      context.strokeRect(cx - size / 2 - 3, cy - size / 2 - 3, size + 6, size + 6);
      context.lineWidth = 3;
      context.strokeStyle = "#ffdd00";
      context.strokeRect(cx - size / 2 - 3, cy - size / 2 - 3, size + 6, size + 6);
    }
    canvas.dataset.scale = String(s);
    canvas.dataset.left = String(view.left);
    canvas.dataset.top = String(view.top);
    byId("zoom-level").textContent = Math.round(s * 100) + "%";
    byId("zoom-out").disabled = s <= fitScale();
    byId("zoom-in").disabled = s >= largestScale();
  }

  // The walk's text as facet step --print writes it: the heading, then each screen under its number
  // and title.
  function showWalk(walk, tile, notice) {
    shown = {walk, tile};
    const [x, y, triangle, heading, screens] = walk;
    byId("pixel").textContent = x + "," + y;
    byId("pixel-triangle").textContent =
        triangle === null ? "(no triangle covers it)" : "(triangle " + triangle + ")";
    byId("notice").hidden = !notice;
    byId("notice").textContent = notice || "";
    const history = byId("history");
    const list = byId("screen-list");
    history.replaceChildren();
    list.replaceChildren();
    const headingLines = document.createElement("pre");
    headingLines.id = "verdict";
    headingLines.textContent = textOf(screenOf(heading, tile)[2], tile);
    history.append(headingLines);
    screens.forEach((screenNumber, k) => {
      const [id, title, body] = screenOf(screenNumber, tile);
      const section = document.createElement("section");
      section.id = "screen-" + (k + 1);
      section.dataset.screen = lineOf(id, tile);
      const h3 = document.createElement("h3");
      h3.textContent = (k + 1) + ". " + lineOf(title, tile);
      const pre = document.createElement("pre");
      pre.textContent = textOf(body, tile);
      section.append(h3, pre);
      history.append(section);
      const item = document.createElement("li");
      const link = document.createElement("a");
      link.href = "#" + section.id;
      link.textContent = h3.textContent;
      link.title = h3.textContent;
      link.addEventListener("click", (event) => {
        event.preventDefault();
        section.scrollIntoView({block: "start"});
      });
      item.append(link);
      list.append(item);
    });
    draw();
    rememberPlace();
  }

  // The first walk at (x, y) in its tile (the opening walk at a grid pixel comes after the grid's).
  function showTraced(x, y, notice, index) {
    const key = tileKey(x, y);
    loadTile(key).then((tile) => {
      const walk = index !== undefined ? tile.walks[index] : tile.walks.find((w) => w[0] === x && w[1] === y);
      if (walk) showWalk(walk, tile, notice);
    }, (error) => {
      byId("notice").hidden = false;
      byId("notice").textContent = "cannot load " + error.message + ": it belongs beside index.html";
    });
  }

  function showPixel(x, y) {
    if (isTraced(x, y)) { showTraced(x, y, ""); return; }
    const nearest = nearestTraced(x, y);
    if (!nearest) return;
    showTraced(nearest[0], nearest[1], "pixel (" + x + ", " + y + ") is not traced; showing the nearest " +
               "traced pixel (" + nearest[0] + ", " + nearest[1] + "); trace it with facet step --pixel " +
               x + "," + y);
  }

  // A click picks the pixel under the pointer; a drag moves the image.
  let press = null;
  canvas.addEventListener("pointerdown", (event) => {
    press = {x: event.clientX, y: event.clientY, left: view.left, top: view.top, dragged: false};
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener("pointermove", (event) => {
    if (!press) return;
    const dx = event.clientX - press.x, dy = event.clientY - press.y;
    if (!press.dragged && dx * dx + dy * dy < 25) return;
    press.dragged = true;
    view.left = press.left + dx;
    view.top = press.top + dy;
    settleView();
    draw();
  });
  canvas.addEventListener("pointerup", (event) => {
    const was = press;
    press = null;
    if (!was || was.dragged) return;
    const box = canvas.getBoundingClientRect();
    const x = Math.floor((event.clientX - box.left - view.left) / view.scale);
    const y = Math.floor((event.clientY - box.top - view.top) / view.scale);
    if (x >= 0 && y >= 0 && x < trace.width && y < trace.height) showPixel(x, y);
  });
  canvas.addEventListener("pointercancel", () => { press = null; });
  canvas.addEventListener("wheel", (event) => {
    event.preventDefault();
    const box = canvas.getBoundingClientRect();
    zoomAt(view.scale * Math.pow(1.0015, -event.deltaY), event.clientX - box.left, event.clientY - box.top);
  }, {passive: false});

  byId("prev").addEventListener("click", () => showStage(stage - 1));
  byId("next").addEventListener("click", () => showStage(stage + 1));
  byId("zoom-in").addEventListener("click", () => zoomBy(2));
  byId("zoom-out").addEventListener("click", () => zoomBy(0.5));
  byId("zoom-fit").addEventListener("click", fit);
  document.addEventListener("keydown", (event) => {
    if (event.ctrlKey || event.altKey || event.metaKey) return;
    const key = event.key;
    if (key === "ArrowRight" || key === "n" || key === "]") showStage(stage + 1);
    else if (key === "ArrowLeft" || key === "b" || key === "[") showStage(stage - 1);
    else if (key === "Home") showStage(0);
    else if (key === "End") showStage(trace.stages.length - 1);
    else if (key === "0") showStage(finalStage);
    else if (key === "+" || key === "=") zoomBy(2);
    else if (key === "-" || key === "_") zoomBy(0.5);
    else if (key === "f") fit();
    else if (key.length === 1 && stageKeys.includes(key)) showStage(stageKeys.indexOf(key));
    else return;
    event.preventDefault();
  });
  byId("theme").addEventListener("click", () => {
    const dark = document.documentElement.classList.toggle("dark");
    byId("theme").textContent = dark ? "Light" : "Dark";
  });

  document.title = "facet step: " + trace.title;
  byId("page-title").textContent = trace.title;
  byId("command-line").textContent = trace.commandLine;
  byId("command-line").title = trace.commandLine;
  trace.stages.forEach((s, n) => {
    const item = document.createElement("li");
    const button = document.createElement("button");
    button.type = "button";
    button.title = s.title;
    if (n < stageKeys.length) {
      const key = document.createElement("kbd");
      key.textContent = stageKeys[n];
      button.append(key, " ");
    }
    button.append(s.title);
    button.addEventListener("click", () => showStage(n));
    item.append(button);
    byId("stage-list").append(item);
  });
  new ResizeObserver(() => { if (view.fitted) fit(); else { settleView(); draw(); } }).observe(canvas);

  // index.html#stage=3&pixel=10,20 opens there (the page keeps its address up to date).
  const place = new URLSearchParams(location.hash.slice(1));
  const stageAsked = Number(place.get("stage"));
  const pixelAsked = (place.get("pixel") || "").split(",").map(Number);
  showStage(Number.isInteger(stageAsked) && stageAsked >= 1 ? stageAsked - 1 : 0);
  fit();
  if (pixelAsked.length === 2 && pixelAsked.every(Number.isInteger) && pixelAsked[0] >= 0 &&
      pixelAsked[1] >= 0 && pixelAsked[0] < trace.width && pixelAsked[1] < trace.height)
    showPixel(pixelAsked[0], pixelAsked[1]);
  else if (trace.opening !== null)
    showTraced(trace.opening[0], trace.opening[1], "", trace.opening[2]);
})();
</script>
<script>
"use strict";
// The notation legend, from trace.notation ([symbol, meaning, where]); ? opens or closes it.
(function () {
  const trace = window.facetStepTrace;
  const legend = document.getElementById("notation");
  if (!trace || !Array.isArray(trace.notation)) return;
  const rows = document.getElementById("notation-rows");
  trace.notation.forEach((entry) => {
    const row = rows.insertRow();
    entry.forEach((field) => { row.insertCell().textContent = field; });
  });
  legend.hidden = false;
  document.addEventListener("keydown", (event) => {
    if (event.key !== "?" || event.ctrlKey || event.altKey || event.metaKey) return;
    legend.open = !legend.open;
    if (legend.open) legend.scrollIntoView({block: "start"});
    event.preventDefault();
  });
})();
</script>
</body>
</html>
)html";

// A tile's file name in kHtmlTileFolder: tile-COLUMN-ROW.js.
std::string tileFileName(int column, int row) {
    return "tile-" + std::to_string(column) + "-" + std::to_string(row) + ".js";
}

}  // namespace

bool PageWalks::Usage::use(std::int64_t tile) {
    if (lastTile == tile) return false;
    if (lastTile != -1) shared = true;
    lastTile = tile;
    return true;
}

std::size_t PageWalks::lineNumber(std::string_view line) {
    if (const auto found = lineNumbers_.find(line); found != lineNumbers_.end()) return found->second;
    const std::string_view kept = lines_.emplace_back(line);
    lineNumbers_.emplace(kept, lineUsage_.size());
    lineUsage_.emplace_back();
    return lineUsage_.size() - 1;
}

std::size_t PageWalks::screenNumber(const std::string& id, const std::string& title,
                                    const std::string& text) {
    std::vector<std::size_t> key = {lineNumber(id), lineNumber(title)};
    // Split at every '\n', the empty line after the last one included: joining with '\n' gives the text back.
    for (std::size_t begin = 0;;) {
        const std::size_t end = text.find('\n', begin);
        key.push_back(lineNumber(std::string_view(text).substr(begin, end - begin)));
        if (end == std::string::npos) break;
        begin = end + 1;
    }
    const auto [at, added] = screenNumbers_.try_emplace(std::move(key), screens_.size());
    if (added) {
        screens_.push_back(at->first);
        screenUsage_.emplace_back();
    }
    return at->second;
}

void PageWalks::useScreen(std::size_t screen, std::int64_t tile) {
    if (!screenUsage_[screen].use(tile)) return;
    for (std::size_t line : screens_[screen])
        lineUsage_[line].use(tile);
}

void PageWalks::add(const Walk& walk) {
    const std::int64_t tile = std::int64_t(walk.y / tileSize_) * tileColumns_ + walk.x / tileSize_;
    CompactWalk compact;
    compact.x = walk.x;
    compact.y = walk.y;
    if (walk.triangle) {
        compact.triangle = walk.triangle->number;
        outlines_.try_emplace(walk.triangle->number, walk.windowPieces);
    }
    // The lines printWalk writes above the screens, from printWalk itself: the page shows them as is.
    compact.heading =
        screenNumber("", "", printWalk({walk.x, walk.y, walk.triangle, walk.verdict, {}, {}, {}}));
    useScreen(compact.heading, tile);
    for (const Screen& screen : walk.screens) {
        compact.screens.push_back(screenNumber(screen.id, screen.title, screen.text));
        useScreen(compact.screens.back(), tile);
    }
    std::vector<CompactWalk>& walks = tiles_[tile];
    places_.emplace_back(tile, walks.size());
    walks.push_back(std::move(compact));
}

// Writes the tiles and the index of a PageWalks: what more than one tile uses goes to the index
// (numbered first), the rest to the one tile that uses it (numbered after the index's).
class PageWriter {
  public:
    explicit PageWriter(const PageWalks& walks) : walks_(walks) {
        for (std::size_t n = 0; n < walks.lineUsage_.size(); ++n)
            if (walks.lineUsage_[n].shared) sharedLine_.emplace(n, sharedLine_.size());
        for (std::size_t n = 0; n < walks.screenUsage_.size(); ++n)
            if (walks.screenUsage_[n].shared) sharedScreen_.emplace(n, sharedScreen_.size());
    }

    // The index's lines and screens.
    json sharedLines() const {
        json lines = json::array();
        for (const auto& [line, number] : ordered(sharedLine_))
            lines.push_back(walks_.lines_[line]);
        return lines;
    }
    json sharedScreens() const {
        json screens = json::array();
        for (const auto& [screen, number] : ordered(sharedScreen_))
            screens.push_back(screenJson(screen, nullptr));
        return screens;
    }

    // One tile's walks, with the lines and screens only it uses.
    json tile(const std::vector<PageWalks::CompactWalk>& tileWalks) const {
        Local local;
        json walks = json::array();
        for (const PageWalks::CompactWalk& walk : tileWalks) {
            json screens = json::array();
            for (std::size_t screen : walk.screens)
                screens.push_back(screenIn(screen, local));
            const std::size_t heading = screenIn(walk.heading, local);
            walks.push_back({walk.x, walk.y, walk.triangle ? json(*walk.triangle) : json(nullptr), heading,
                             std::move(screens)});
        }
        return {{"lines", std::move(local.lineTexts)},
                {"screens", std::move(local.screenEntries)},
                {"walks", std::move(walks)}};
    }

  private:
    struct Local {
        std::unordered_map<std::size_t, std::size_t> lines, screens;  // PageWalks' number → the tile's
        json lineTexts = json::array(), screenEntries = json::array();
    };

    static std::vector<std::pair<std::size_t, std::size_t>> ordered(
        const std::unordered_map<std::size_t, std::size_t>& numbers) {
        std::vector<std::pair<std::size_t, std::size_t>> pairs(numbers.begin(), numbers.end());
        std::sort(pairs.begin(), pairs.end(),
                  [](const auto& a, const auto& b) { return a.second < b.second; });
        return pairs;
    }

    std::size_t lineIn(std::size_t line, Local* local) const {
        if (const auto shared = sharedLine_.find(line); shared != sharedLine_.end()) return shared->second;
        const auto [at, added] = local->lines.try_emplace(line, sharedLine_.size() + local->lines.size());
        if (added) local->lineTexts.push_back(walks_.lines_[line]);
        return at->second;
    }

    // [id, title, [text lines]], numbers into the index's lines then the tile's.
    json screenJson(std::size_t screen, Local* local) const {
        const std::vector<std::size_t>& lines = walks_.screens_[screen];
        const auto number = [&](std::size_t line) {
            return local ? lineIn(line, local) : sharedLine_.at(line);
        };
        json text = json::array();
        for (std::size_t k = 2; k < lines.size(); ++k)
            text.push_back(number(lines[k]));
        return json::array({number(lines[0]), number(lines[1]), std::move(text)});
    }

    std::size_t screenIn(std::size_t screen, Local& local) const {
        if (const auto shared = sharedScreen_.find(screen); shared != sharedScreen_.end())
            return shared->second;
        const auto found = local.screens.find(screen);
        if (found != local.screens.end()) return found->second;
        const std::size_t number = sharedScreen_.size() + local.screens.size();
        local.screens.emplace(screen, number);
        local.screenEntries.push_back(screenJson(screen, &local));
        return number;
    }

    const PageWalks& walks_;
    std::unordered_map<std::size_t, std::size_t> sharedLine_, sharedScreen_;  // PageWalks' → the index's
};

void writeHtmlPage(const fs::path& dir, const HtmlPage& page, const PageWalks& walks) {
    std::error_code error;
    fs::create_directories(dir / kHtmlTileFolder, error);
    if (error)
        throw InputError((dir / kHtmlTileFolder).string() + ": cannot make the folder: " + error.message());
    // Invalid UTF-8 in a text (a file name from the command line) becomes U+FFFD instead of an exception.
    const auto dump = [](const json& value) {
        return value.dump(-1, ' ', false, json::error_handler_t::replace);
    };

    const PageWriter writer(walks);
    json tiles = json::array();
    for (const auto& [tile, tileWalks] : walks.tiles_) {
        const int column = int(tile % walks.tileColumns_), row = int(tile / walks.tileColumns_);
        tiles.push_back({column, row});
        writeTextFile(dir / kHtmlTileFolder / tileFileName(column, row),
                      "// facet step --html: the walks of one tile (index.html describes the format).\n"
                      "facetStepTile(\"" +
                          std::to_string(column) + "," + std::to_string(row) + "\", " +
                          dump(writer.tile(tileWalks)) + ");\n");
    }

    json stages = json::array();
    for (const StageImage& stage : page.stages)
        stages.push_back({{"id", stage.id},
                          {"title", stage.title},
                          {"file", stage.file},
                          {"description", stage.description}});
    json outlines = json::object();
    for (const auto& [triangle, pieces] : walks.outlines_)
        outlines[std::to_string(triangle)] = pieces;
    json opening = nullptr;
    if (page.firstWalk < walks.places_.size()) {
        const auto [tile, index] = walks.places_[page.firstWalk];
        const PageWalks::CompactWalk& walk = walks.tiles_.at(tile)[index];
        opening = {walk.x, walk.y, index};
    }
    json notationRows = json::array();
    for (const Symbol& s : notation())
        notationRows.push_back({std::string(s.symbol), std::string(s.meaning), std::string(s.where)});
    const json region =
        page.region ? json::array({page.region->x, page.region->y, page.region->width, page.region->height})
                    : json(nullptr);
    const json data = {{"width", page.width},
                       {"height", page.height},
                       {"title", page.title},
                       {"commandLine", page.commandLine},
                       {"gridStep", page.gridStep},
                       {"region", region},
                       {"tileSize", walks.tileSize()},
                       {"tiles", std::move(tiles)},
                       {"opening", std::move(opening)},
                       {"stages", std::move(stages)},
                       {"outlines", std::move(outlines)},
                       {"lines", writer.sharedLines()},
                       {"screens", writer.sharedScreens()},
                       {"notation", std::move(notationRows)}};
    writeTextFile(dir / kHtmlDataFile,
                  "// facet step --html: the index of the trace index.html shows (index.html describes the "
                  "format).\nwindow.facetStepTrace = " +
                      dump(data) + ";\n");
    // The data first: the page is complete once index.html appears.
    writeTextFile(dir / kHtmlPageFile, kIndexHtml);
}

void writeHtmlPage(const fs::path& dir, const HtmlPage& page) {
    PageWalks walks(page.width);
    for (const Walk& walk : page.walks)
        walks.add(walk);
    writeHtmlPage(dir, page, walks);
}

}  // namespace facet::step
