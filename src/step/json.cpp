// The trace as JSON (facet step --json): plain data a web page or a script reads; every number as the
// pipeline computed it, names from the name tables.
#include "step/walk.h"

namespace facet::step {

namespace {

using nlohmann::json;

json vectorJson(const vec2& v) {
    return json::array({v.x, v.y});
}
json vectorJson(const vec3& v) {
    return json::array({v.x, v.y, v.z});
}
json vectorJson(const vec4& v) {
    return json::array({v.x, v.y, v.z, v.w});
}
json matrixJson(const mat4& m) {  // rows
    json rows = json::array();
    for (int row = 0; row < 4; ++row)
        rows.push_back(json::array({m[0][row], m[1][row], m[2][row], m[3][row]}));
    return rows;
}

json refJson(const TriangleRef& ref) {
    return {{"number", ref.number}, {"draw", ref.draw}, {"triangleInDraw", ref.triangle}};
}

json coverageJson(const CoverageEvent& e) {
    return {{"edgeValues", e.edgeValues},     {"tiedEdges", e.tiedEdges},
            {"topLeftEdges", e.topLeftEdges}, {"excludingEdges", e.excludingEdges},
            {"covered", e.covered},           {"culled", e.culled}};
}

json fragmentJson(const FragmentEvent& f) {
    return {{"depth", f.depth},
            {"depthBefore", f.depthBefore},
            {"fate", nameOf(f.fate)},
            {"shaded", vectorJson(f.shaded)},
            {"colorBefore", vectorJson(f.colorBefore)},
            {"colorAfter", vectorJson(f.colorAfter)},
            {"barycentrics", vectorJson(f.barycentrics)},
            {"invW", f.invW},
            {"varyings", std::vector<float>(f.varyings.begin(), f.varyings.begin() + f.varyingCount)}};
}

json pixelJson(const PixelTrace& p) {
    json triangles = json::array();
    for (const TriangleAtPixel& e : p.triangles) {
        json t = {{"triangle", refJson(e.ref)}, {"drawCall", e.call},
                  {"fate", nameOf(e.fate)},     {"depthCompare", nameOf(e.depthCompare)},
                  {"blend", nameOf(e.blend)},   {"transparent", e.transparent}};
        if (e.coverage) t["coverage"] = coverageJson(*e.coverage);
        if (e.fragment) t["fragment"] = fragmentJson(*e.fragment);
        if (e.sortPlace) t["transparentPlace"] = *e.sortPlace;
        if (e.tieOwner) t["tieOwner"] = refJson(*e.tieOwner);
        if (e.overwrittenBy) t["overwrittenBy"] = refJson(*e.overwrittenBy);
        triangles.push_back(std::move(t));
    }
    json pixel = {{"x", p.x},
                  {"y", p.y},
                  {"clearColor", vectorJson(p.clearColor)},
                  {"triangles", std::move(triangles)},
                  {"finalColor", vectorJson(p.finalColor)},
                  {"finalBytes", p.finalBytes},
                  {"encoding", nameOf(p.encoding.curve)}};
    if (p.producer) pixel["producer"] = *p.producer;
    if (p.resolve) {
        json fragments = json::array();
        for (const ResolvedFragment& f : p.resolve->fragments)
            fragments.push_back({{"submission", f.submission},
                                 {"depth", f.depth},
                                 {"blend", nameOf(f.blend)},
                                 {"color", vectorJson(f.color)},
                                 {"colorAfter", vectorJson(f.colorAfter)}});
        json submitted = json::array();
        for (const TriangleRef& ref : p.resolve->submitted)
            submitted.push_back(refJson(ref));
        pixel["resolve"] = {{"colorBefore", vectorJson(p.resolve->colorBefore)},
                            {"stored", std::move(submitted)},
                            {"composited", std::move(fragments)}};
    }
    return pixel;
}

json windowVertexJson(const WindowVertex& v) {
    return {{"window", vectorJson(v.window)},
            {"xFixed", v.xFixed},
            {"yFixed", v.yFixed},
            {"z", v.z},
            {"invW", v.invW}};
}

json triangleJson(const TriangleTrace& t) {
    json vertices = json::array();
    for (int k = 0; k < 3; ++k)
        vertices.push_back({{"index", t.indices[k]},
                            {"object", vectorJson(t.objectPositions[k])},
                            {"normal", vectorJson(t.objectNormals[k])},
                            {"clip", vectorJson(t.clipPositions[k])},
                            {"outcode", clipPlaneNames(t.outcodes[k])}});
    json steps = json::array();
    for (const ClipStep& step : t.clipSteps) {
        json made = json::array();
        for (const ClipStep::NewVertex& v : step.made)
            made.push_back(
                {{"from", v.from}, {"to", v.to}, {"t", v.t}, {"position", vectorJson(v.position)}});
        json polygon = json::array();
        for (const vec4& p : step.polygon)
            polygon.push_back(vectorJson(p));
        steps.push_back({{"plane", clipPlaneNames(step.plane)}, {"made", made}, {"polygon", polygon}});
    }
    json pieces = json::array();
    for (const WindowPiece& piece : t.pieces) {
        json edges = json::array();
        for (const EdgeFunction& e : piece.setup.edges)
            edges.push_back({{"a", e.a}, {"b", e.b}, {"c", e.c}, {"bias", e.bias()}});
        pieces.push_back({{"vertices",
                           {windowVertexJson(piece.vertices[0]), windowVertexJson(piece.vertices[1]),
                            windowVertexJson(piece.vertices[2])}},
                          {"signedDoubleArea", piece.signedDoubleArea},
                          {"fate", nameOf(piece.fate)},
                          {"frontFacing", piece.setup.frontFacing},
                          {"edges", edges},
                          {"box", {piece.setup.minX, piece.setup.minY, piece.setup.maxX, piece.setup.maxY}},
                          {"tiles", piece.tiles}});
    }
    std::vector<std::string> raster;
    for (int row = 0; row < t.rasterHeight; ++row)
        raster.emplace_back(t.raster.begin() + row * t.rasterWidth,
                            t.raster.begin() + (row + 1) * t.rasterWidth);
    json triangle = {
        {"triangle", refJson(t.ref)},
        {"drawCall", t.call},
        {"vertices", vertices},
        {"worldFromObject", matrixJson(t.worldFromObject)},
        {"viewFromWorld", matrixJson(t.viewFromWorld)},
        {"clipFromView", matrixJson(t.clipFromView)},
        {"clipSteps", steps},
        {"pieces", pieces},
        {"tileSize", t.tileSize},
        {"raster",
         {{"left", t.focusX - t.rasterWidth / 2}, {"top", t.focusY - t.rasterHeight / 2}, {"rows", raster}}}};
    if (t.rejected) triangle["rejected"] = nameOf(*t.rejected);
    if (!t.vertexVaryings[0].empty())
        triangle["vertexVaryings"] = {t.vertexVaryings[0], t.vertexVaryings[1], t.vertexVaryings[2]};
    return triangle;
}

}  // namespace

nlohmann::json toJson(const StepTrace& trace) {
    json screens = json::array();
    for (const Screen& s : trace.walk.screens)
        screens.push_back({{"id", s.id}, {"title", s.title}, {"text", s.text}});
    json out = {{"pixel", pixelJson(trace.pixel)}, {"verdict", trace.walk.verdict}, {"screens", screens}};
    if (trace.triangle) out["triangle"] = triangleJson(*trace.triangle);
    if (trace.shading) out["shading"] = toJson(*trace.shading);
    if (trace.userShader) out["userShader"] = toJson(*trace.userShader);
    return out;
}

}  // namespace facet::step
