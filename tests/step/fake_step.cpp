// A stand-in for `facet step` while it is being written: `fake_step step MODEL --html DIR` and
// `fake_step step MODEL --pixel X,Y --print`, from hand-made walks of a 40×30 frame with one triangle.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "io/image_io.h"
#include "step/html_page.h"

using namespace facet;
using namespace facet::step;

constexpr int kWidth = 40, kHeight = 30, kStep = 4;

static bool inside(int x, int y) {
    return y >= 5 && x >= 5 && x - 5 <= (y - 5) * 1.2;
}

static Walk walkAt(int x, int y) {
    Walk walk;
    walk.x = x;
    walk.y = y;
    if (inside(x, y)) {
        walk.triangle = TriangleRef{0, 0, 0};
        walk.verdict = "triangle 0 wrote its colour";
        walk.screens = {{"clip", "Clipping: no plane cuts triangle 0", "w = 1 > 0 at every vertex\n"},
                        {"shade", "Shading: c = k_d max(N·L, 0)",
                         "c = 0.8 × max(" + std::to_string(x * 0.01) + ", 0) = " + std::to_string(x * 0.008) +
                             "\n  next line   with  spaces\n"},
                        {"history", "Pixel history", "triangle 0: written\n"}};
    } else {
        walk.verdict = "no triangle covers it: the clear colour";
        walk.screens = {{"history", "Pixel history", "no triangle's box holds the pixel\n"}};
    }
    return walk;
}

int main(int argc, char** argv) {
    std::string html, pixel;
    bool print = false;
    for (int i = 2; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--html") && i + 1 < argc) html = argv[++i];
        if (!std::strcmp(argv[i], "--pixel") && i + 1 < argc) pixel = argv[++i];
        if (!std::strcmp(argv[i], "--print")) print = true;
    }
    if (print) {
        int x = 0, y = 0;
        std::sscanf(pixel.c_str(), "%d,%d", &x, &y);
        std::cout << printWalk(walkAt(x, y));
        return 0;
    }
    HtmlPage page;
    page.width = kWidth;
    page.height = kHeight;
    page.title = "fake";
    page.commandLine = "fake_step step fake.obj --html " + html;
    page.gridStep = kStep;
    const char* names[] = {"clip", "final", "build-001"};
    for (int s = 0; s < 3; ++s) {
        LinearImage image;
        image.width = kWidth;
        image.height = kHeight;
        image.pixels.assign(kWidth * kHeight, glm::vec4(0.1f, 0.1f, 0.2f, 1.0f));
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                if (inside(x, y)) image.at(x, y) = glm::vec4(s == 0, s == 1, s == 2, 1.0f);
        std::filesystem::create_directories(html);
        const std::string file = "stage-" + std::to_string(s + 1) + "-" + names[s] + ".png";
        writeImage(std::filesystem::path(html) / file, image);
        page.stages.push_back({names[s], std::string("Stage ") + names[s], file, "A made-up image."});
    }
    for (int y = 0; y < kHeight; y += kStep)
        for (int x = 0; x < kWidth; x += kStep)
            page.walks.push_back(walkAt(x, y));
    writeHtmlPage(html, page);
}
