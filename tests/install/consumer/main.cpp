// A program of one's own against an installed Facet (tests/install/find_package_test.sh): draws the
// README's gradient triangle and checks it was drawn. Built through find_package(Facet) it also loads an
// OBJ model and writes the triangle to a PNG file (FACET_CONSUMER_IO); built through pkg-config (the
// pipeline alone) it only draws.
#include <cstdio>

#include "readme_example.h"
#if FACET_CONSUMER_IO
#include "base/errors.h"
#include "io/image_io.h"
#include "io/obj_import.h"
#endif

int main(int argc, char** argv) {
    const facet::Framebuffer image = drawGradientTriangle();
    const facet::vec4 clear(0.0f, 0.0f, 0.0f, 1.0f);
    // The centre lies inside the triangle, the top corners outside it.
    if (image.color(32, 40) == clear || image.color(0, 0) != clear || image.color(63, 0) != clear) {
        std::fprintf(stderr, "consumer: the triangle was not drawn as the README says\n");
        return 1;
    }
    std::printf("consumer: drew the README's triangle\n");
#if FACET_CONSUMER_IO
    if (argc != 3) {
        std::fprintf(stderr, "usage: consumer MODEL.obj OUTPUT.png\n");
        return 2;
    }
    try {
        const facet::Mesh mesh = facet::loadObj(argv[1]);
        facet::LinearImage out{image.width(), image.height(), {}};
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                out.pixels.push_back(image.color(x, y));
        facet::writeImage(argv[2], out);
        std::printf("consumer: loaded %zu triangles, wrote %s\n", mesh.indices.size() / 3, argv[2]);
    } catch (const facet::InputError& error) {
        std::fprintf(stderr, "consumer: %s\n", error.what());
        return 1;
    }
#else
    (void)argc;
    (void)argv;
#endif
    return 0;
}
