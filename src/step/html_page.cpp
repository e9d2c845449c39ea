#include "step/html_page.h"

#include <array>
#include <deque>
#include <map>
#include <string_view>
#include <unordered_map>

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

  Files: index.html (this page, the same for every trace), trace-data.js (the trace, a script that sets
  the global facetStepTrace, since a page opened from file:// cannot fetch JSON), and the stage images.

  trace-data.js holds one object:
    width, height       the frame's size in pixels
    title, commandLine  the heading, and the facet step command that made the page
    gridStep            pixels traced every gridStep in x and y (1: every pixel)
    firstWalk           index of the walk shown when the page opens
    stages              [{id, title, file, description}], pipeline order; id "final" is the finished frame
    strings             every distinct text once: screen ids, titles and texts, verdicts
    screens             every distinct screen once: [id, title, text], numbers into strings
    walks               one per traced pixel: [x, y, triangle (null: none), heading, [screen numbers]];
                        the heading is the lines facet step --print writes above the screens (the
                        pixel, its triangle, the verdict), a number into strings
    notation            [[symbol, meaning, where]]: the symbols the screens print, for the legend
  Walks share screens (the triangle's views, background pixels), so a screen costs its size once.
  Size: the Stanford bunny at 800x600 with every 8th pixel traced (7500 walks, 1459 on the bunny) gives a
  trace-data.js of 13.8 MB, where the walks' printed text is 22.5 MB (the background pixels share all
  but their history); every 4th pixel, 55 MB. Chromium opens either in under 2 s.
-->
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>facet step</title>
<style>
  :root { --bg: #ffffff; --fg: #000000; --muted: #303030; --panel: #eeeeee; --accent: #0033aa;
          --marker: #ffdd00; --marker-edge: #000000; }
  html.dark { --bg: #000000; --fg: #ffffff; --muted: #dddddd; --panel: #1c1c1c; --accent: #99ccff; }
  html, body { margin: 0; background: var(--bg); color: var(--fg); }
  body { font: 20px/1.4 sans-serif; }
  header { display: flex; flex-wrap: wrap; align-items: baseline; gap: 0.3em 1em; padding: 0.5em 1em;
           border-bottom: 2px solid var(--fg); }
  header h1 { font-size: 1.4em; margin: 0; }
  #command-line { font: 18px monospace; color: var(--muted); overflow-wrap: anywhere; flex: 1 1 20em; }
  button { font: inherit; color: var(--fg); background: var(--panel); border: 2px solid var(--fg);
           border-radius: 4px; padding: 0.1em 0.6em; cursor: pointer; }
  button:disabled { opacity: 0.4; cursor: default; }
  main { display: flex; flex-wrap: wrap; gap: 1em; padding: 1em; align-items: flex-start; }
  /* Side by side when the window holds the image's 20em and 80 columns of text, else one above the other. */
  #stage-panel { flex: 1 1 20em; min-width: 0; }
  #pixel-panel { flex: 0 1 auto; width: min-content; max-width: 100%; }
  /* Side by side, the image stays in view while the screens scroll past it. */
  @media (min-width: 1200px) {
    #stage-panel { position: sticky; top: 0; max-height: 100vh; overflow-y: auto; overflow-x: hidden; }
  }
  #stage-nav { display: flex; align-items: center; gap: 1em; }
  h2 { font-size: 1.3em; margin: 0.4em 0; }
  #stage-description { color: var(--muted); margin: 0 0 0.6em 0; }
  #image-frame { position: relative; display: inline-block; line-height: 0; border: 2px solid var(--fg);
                 cursor: crosshair; }
  #stage-image { display: block; image-rendering: pixelated; image-rendering: crisp-edges; }
  #marker { position: absolute; box-sizing: border-box; border: 3px solid var(--marker);
            outline: 2px solid var(--marker-edge); pointer-events: none; }
  #stage-list { padding-left: 0; list-style: none; display: flex; flex-wrap: wrap; gap: 0.3em; }
  #stage-list button { font-size: 0.8em; text-align: left; }
  #stage-list button[aria-current="true"] { background: var(--fg); color: var(--bg); }
  .hint { color: var(--muted); font-size: 0.85em; }
  #notice { border: 2px solid var(--fg); background: var(--panel); padding: 0.4em 0.6em; }
  #screen-list { margin: 0.3em 0; padding-left: 1.5em; columns: 2 18em; }
  #screen-list a { color: var(--accent); }
  #history #verdict { background: none; padding: 0; font: bold clamp(16px, 1.05vw, 26px)/1.35 monospace; margin: 0.5em 0; white-space: pre-wrap; }
  #history section { border-top: 2px solid var(--fg); margin-top: 1em; }
  #history h3 { font-size: 1.1em; margin: 0.4em 0; }
  /* 80 columns (a screen's width) as large as the window allows: 16 to 26 px (Ctrl + for more). */
  #history pre { font: clamp(16px, 1.05vw, 26px)/1.35 monospace; width: 80ch; max-width: 100%;
                 margin: 0; padding: 0.5em; background: var(--panel); overflow-x: auto; }
  #load-error { margin: 1em; font-weight: bold; }
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
    <div id="stage-nav">
      <button id="prev" type="button" title="Previous stage (left arrow or b)">&larr; Previous</button>
      <span id="stage-counter"></span>
      <button id="next" type="button" title="Next stage (right arrow or n)">Next &rarr;</button>
    </div>
    <h2 id="stage-title"></h2>
    <p id="stage-description"></p>
    <div id="image-frame"><img id="stage-image" alt=""><div id="marker"></div></div>
    <p class="hint">Click a pixel to see its history. Keys: &larr; &rarr; (or b, n) previous and next
      stage; 1 to 9 jump to that stage, 0 to the final image; ? the notation.</p>
    <ol id="stage-list"></ol>
  </section>
  <section id="pixel-panel">
    <h2>Pixel <span id="pixel"></span> <span id="pixel-triangle"></span></h2>
    <p id="notice" hidden></p>
    <nav><ol id="screen-list"></ol></nav>
    <div id="history"></div>
  </section>
</main>
<details id="notation" hidden>
  <summary>Notation: the symbols the screens print (key ?)</summary>
  <table><thead><tr><th>Symbol</th><th>Meaning</th><th>Screens</th></tr></thead>
    <tbody id="notation-rows"></tbody></table>
</details>
<script src="trace-data.js"></script>
<script>
"use strict";
(function () {
  const byId = (id) => document.getElementById(id);
  const trace = window.facetStepTrace;
  if (!trace || !trace.walks || !trace.stages) {
    byId("data-error").hidden = false;
    return;
  }
  const text = (n) => trace.strings[n];
  const image = byId("stage-image");
  const marker = byId("marker");
  let stage = 0;
  // The finished frame (the build-up frames may follow it); key 0 jumps to it.
  const finalFound = trace.stages.findIndex((s) => s.id === "final");
  const finalStage = finalFound >= 0 ? finalFound : trace.stages.length - 1;
  let shownWalk = Math.min(trace.firstWalk, trace.walks.length - 1);

  // A walk is [x, y, triangle, heading, screens]; the first one at a pixel is the one shown.
  const walkAtPixel = new Map();
  trace.walks.forEach((walk, n) => {
    const key = walk[1] * trace.width + walk[0];
    if (!walkAtPixel.has(key)) walkAtPixel.set(key, n);
  });

  // The traced pixel nearest to (x, y) in Euclidean distance; the first in trace order on a tie.
  function nearestWalk(x, y) {
    let best = -1, bestDistance = Infinity;
    trace.walks.forEach((walk, n) => {
      const d = (walk[0] - x) * (walk[0] - x) + (walk[1] - y) * (walk[1] - y);
      if (d < bestDistance) { best = n; bestDistance = d; }
    });
    return best;
  }

  function fileUrl(file) { return file.split("/").map(encodeURIComponent).join("/"); }

  function rememberPlace() {
    const walk = trace.walks[shownWalk];
    const place = "#stage=" + (stage + 1) + (walk ? "&pixel=" + walk[0] + "," + walk[1] : "");
    try { history.replaceState(null, "", place); } catch (e) { /* some browsers refuse on file:// */ }
  }

  function showStage(n) {
    if (n < 0 || n >= trace.stages.length) return;
    stage = n;
    const s = trace.stages[n];
    image.src = fileUrl(s.file);
    image.alt = s.title;
    byId("stage-title").textContent = s.title;
    byId("stage-description").textContent = s.description;
    byId("stage-counter").textContent = "Stage " + (n + 1) + " of " + trace.stages.length;
    byId("prev").disabled = n === 0;
    byId("next").disabled = n === trace.stages.length - 1;
    byId("stage-list").querySelectorAll("button").forEach((button, k) => {
      button.setAttribute("aria-current", k === n ? "true" : "false");
    });
    rememberPlace();
  }

  // The image as large as the panel and most of the window allow, pixels kept square and sharp.
  function layoutImage() {
    const available = byId("stage-panel").clientWidth - 4;
    const scale = Math.max(0.1, Math.min(available / trace.width, (window.innerHeight * 0.75) / trace.height));
    image.style.width = trace.width * scale + "px";
    image.style.height = trace.height * scale + "px";
    placeMarker();
  }

  // A box around the shown pixel, at least 14 screen pixels wide so it shows on a small scale.
  function placeMarker() {
    const walk = trace.walks[shownWalk];
    if (!walk) { marker.hidden = true; return; }
    const cell = image.clientWidth / trace.width;
    const size = Math.max(cell + 6, 14);
    marker.hidden = false;
    marker.style.width = marker.style.height = size + "px";
    marker.style.left = (walk[0] + 0.5) * cell - size / 2 + "px";
    marker.style.top = (walk[1] + 0.5) * cell - size / 2 + "px";
  }

  // The walk's text as facet step --print writes it: the heading, then each screen under its number
  // and title.
  function showWalk(n, notice) {
    const walk = trace.walks[n];
    if (!walk) return;
    shownWalk = n;
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
    headingLines.textContent = text(heading);
    history.append(headingLines);
    screens.forEach((screenNumber, k) => {
      const [id, title, body] = trace.screens[screenNumber];
      const section = document.createElement("section");
      section.id = "screen-" + (k + 1);
      section.dataset.screen = text(id);
      const h3 = document.createElement("h3");
      h3.textContent = (k + 1) + ". " + text(title);
      const pre = document.createElement("pre");
      pre.textContent = text(body);
      section.append(h3, pre);
      history.append(section);
      const item = document.createElement("li");
      const link = document.createElement("a");
      link.href = "#" + section.id;
      link.textContent = text(title);
      link.addEventListener("click", (event) => {
        event.preventDefault();
        section.scrollIntoView({block: "start"});
      });
      item.append(link);
      list.append(item);
    });
    placeMarker();
    rememberPlace();
  }

  function showPixel(x, y) {
    const exact = walkAtPixel.get(y * trace.width + x);
    if (exact !== undefined) { showWalk(exact, ""); return; }
    const n = nearestWalk(x, y);
    if (n < 0) return;
    const walk = trace.walks[n];
    showWalk(n, "pixel (" + x + ", " + y + ") is not traced; showing the nearest traced pixel (" +
                    walk[0] + ", " + walk[1] + "); trace it with facet step --pixel " + x + "," + y);
  }

  image.addEventListener("click", (event) => {
    const box = image.getBoundingClientRect();
    const clamp = (v, hi) => Math.min(Math.max(v, 0), hi - 1);
    const x = clamp(Math.floor((event.clientX - box.left) / box.width * trace.width), trace.width);
    const y = clamp(Math.floor((event.clientY - box.top) / box.height * trace.height), trace.height);
    showPixel(x, y);
  });

  byId("prev").addEventListener("click", () => showStage(stage - 1));
  byId("next").addEventListener("click", () => showStage(stage + 1));
  document.addEventListener("keydown", (event) => {
    if (event.ctrlKey || event.altKey || event.metaKey) return;
    const key = event.key;
    if (key === "ArrowRight" || key === "n") showStage(stage + 1);
    else if (key === "ArrowLeft" || key === "b") showStage(stage - 1);
    else if (key === "0") showStage(finalStage);
    else if (key >= "1" && key <= "9") showStage(Number(key) - 1);
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
  trace.stages.forEach((s, n) => {
    const item = document.createElement("li");
    const button = document.createElement("button");
    button.type = "button";
    button.textContent = (n + 1) + " " + s.title;
    button.addEventListener("click", () => showStage(n));
    item.append(button);
    byId("stage-list").append(item);
  });
  window.addEventListener("resize", layoutImage);

  // index.html#stage=3&pixel=10,20 opens there (the page keeps its address up to date).
  const place = new URLSearchParams(location.hash.slice(1));
  const stageAsked = Number(place.get("stage"));
  const pixelAsked = (place.get("pixel") || "").split(",").map(Number);
  showStage(Number.isInteger(stageAsked) && stageAsked >= 1 ? stageAsked - 1 : 0);
  if (pixelAsked.length === 2 && pixelAsked.every(Number.isInteger)) showPixel(pixelAsked[0], pixelAsked[1]);
  else showWalk(shownWalk, "");
  layoutImage();
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

// Numbers each distinct string once, in order of first use; the views point into the page being written.
class StringTable {
  public:
    std::size_t number(std::string_view text) {
        const auto [at, added] = numbers_.try_emplace(text, strings_.size());
        if (added) strings_.push_back(text);
        return at->second;
    }
    json toJson() const {
        json array = json::array();
        for (std::string_view text : strings_)
            array.push_back(std::string(text));
        return array;
    }

  private:
    std::unordered_map<std::string_view, std::size_t> numbers_;
    std::vector<std::string_view> strings_;
};

json traceData(const HtmlPage& page) {
    json stages = json::array();
    for (const StageImage& stage : page.stages)
        stages.push_back({{"id", stage.id},
                          {"title", stage.title},
                          {"file", stage.file},
                          {"description", stage.description}});

    std::deque<std::string> headings;  // outlives `strings`, which refers to them
    StringTable strings;
    std::map<std::array<std::size_t, 3>, std::size_t> screenNumbers;  // [id, title, text] → its number
    json screens = json::array();
    json walks = json::array();
    for (const Walk& walk : page.walks) {
        json walkScreens = json::array();
        for (const Screen& screen : walk.screens) {
            const std::array<std::size_t, 3> key = {strings.number(screen.id), strings.number(screen.title),
                                                    strings.number(screen.text)};
            const auto [at, added] = screenNumbers.try_emplace(key, screens.size());
            if (added) screens.push_back(key);
            walkScreens.push_back(at->second);
        }
        const json triangle = walk.triangle ? json(walk.triangle->number) : json(nullptr);
        // The lines printWalk writes above the screens, from printWalk itself: the page shows them as is.
        const std::string& heading =
            headings.emplace_back(printWalk({walk.x, walk.y, walk.triangle, walk.verdict, {}}));
        walks.push_back({walk.x, walk.y, triangle, strings.number(heading), std::move(walkScreens)});
    }
    json notationRows = json::array();
    for (const Symbol& s : notation())
        notationRows.push_back({std::string(s.symbol), std::string(s.meaning), std::string(s.where)});
    return {{"width", page.width},
            {"height", page.height},
            {"title", page.title},
            {"commandLine", page.commandLine},
            {"gridStep", page.gridStep},
            {"firstWalk", page.firstWalk},
            {"stages", std::move(stages)},
            {"strings", strings.toJson()},
            {"screens", std::move(screens)},
            {"walks", std::move(walks)},
            {"notation", std::move(notationRows)}};
}

}  // namespace

void writeHtmlPage(const fs::path& dir, const HtmlPage& page) {
    std::error_code error;
    fs::create_directories(dir, error);
    if (error) throw InputError(dir.string() + ": cannot make the folder: " + error.message());

    // Invalid UTF-8 in a text (a file name from the command line) becomes U+FFFD instead of an exception.
    const std::string data =
        "// facet step --html: the trace index.html shows (the format is described at the top of "
        "index.html).\nwindow.facetStepTrace = " +
        traceData(page).dump(-1, ' ', false, json::error_handler_t::replace) + ";\n";
    // The data first: the page is complete once index.html appears.
    writeTextFile(dir / kHtmlDataFile, data);
    writeTextFile(dir / kHtmlPageFile, kIndexHtml);
}

}  // namespace facet::step
