// Ray-cast shadows drawn: a square floating above a ground plane under a point light casts the shadow
// geometry predicts (its corners projected from the light onto the ground), pixel for pixel away from
// the outline; in shadow a pixel keeps exactly its ambient and emission and loses its diffuse and
// specular; a scene without shadowing lights builds no BVH; the BVH survives triangles Embree must not
// see and moves with the turntable.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render/renderer.h"
#include "scene/scene.h"
#include "support/analytic_shadow.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using namespace analytic_shadow;

// ---- the shadow where geometry puts it ---------------------------------------------------------------

// Every ground pixel more than 1.5 px from the outline is dark inside the projected square and lit
// outside it. Breaks if visibility is ignored (lighting.h: no pixel dark), if the shadow ray goes the
// wrong way or to the wrong place (dark pixels elsewhere), or if the ray's origin is not lifted off
// the surface (ε = 0: the ground shadows itself, acne).
TEST_F(ShadowTest, RayShadowIsTheSquareProjectedFromTheLight) {
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    const LinearImage image = render(prepared);
    EXPECT_EQ(shadowDisagreements(image, pixels, darkLitThreshold(prepared, pixels)), 0u);
}

// In shadow a pixel is exactly its ambient and emission (as the ambient-only image draws them), and
// outside it exactly the unshadowed image: the shadow takes the light's diffuse and specular, and only
// where the ray is blocked. The ambient-only image is the same with shadows or without; the
// diffuse-only image is black in the shadow. Breaks if the visibility also scales the ambient term
// (or the emission), or scales a lit pixel by anything but 1, or is ignored for the specular term.
TEST_F(ShadowTest, ShadowKeepsAmbientAndEmissionAndTakesDiffuseAndSpecular) {
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene shadowed = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const PreparedScene unshadowed = prepareScene(loadScene(writeScene(scene, "\"none\"")));
    const std::vector<GroundPixel> pixels = checkedPixels(scene, shadowed);

    const LinearImage ambientShadowed = render(shadowed, kAmbientTerm | kEmissionTerm);
    const LinearImage ambientUnshadowed = render(unshadowed, kAmbientTerm | kEmissionTerm);
    EXPECT_EQ(ambientShadowed.pixels, ambientUnshadowed.pixels);
    const LinearImage ambientOnly = render(shadowed, kAmbientTerm);
    const LinearImage emissionOnly = render(shadowed, kEmissionTerm);
    EXPECT_EQ(ambientOnly.pixels, render(unshadowed, kAmbientTerm).pixels);
    EXPECT_EQ(emissionOnly.pixels, render(unshadowed, kEmissionTerm).pixels);

    const LinearImage full = render(shadowed), fullUnshadowed = render(unshadowed);
    const LinearImage diffuse = render(shadowed, kDiffuseTerm), specular = render(shadowed, kSpecularTerm);
    const LinearImage diffuseUnshadowed = render(unshadowed, kDiffuseTerm);
    const LinearImage specularUnshadowed = render(unshadowed, kSpecularTerm);
    std::size_t inShadow = 0, specularInShadow = 0;
    for (const GroundPixel& p : pixels) {
        SCOPED_TRACE(testing::Message() << "pixel " << p.x << ", " << p.y);
        if (p.inShadow) {
            ++inShadow;
            ASSERT_EQ(full.at(p.x, p.y), ambientShadowed.at(p.x, p.y));
            ASSERT_EQ(diffuse.at(p.x, p.y), vec4(0, 0, 0, 1));
            ASSERT_EQ(specular.at(p.x, p.y), vec4(0, 0, 0, 1));
            ASSERT_GT(brightness(diffuseUnshadowed.at(p.x, p.y)), 0.1);
            specularInShadow += brightness(specularUnshadowed.at(p.x, p.y)) > 0.01;
        } else {
            ASSERT_EQ(full.at(p.x, p.y), fullUnshadowed.at(p.x, p.y));
            ASSERT_EQ(diffuse.at(p.x, p.y), diffuseUnshadowed.at(p.x, p.y));
        }
    }
    EXPECT_GT(inShadow, 400u);
    EXPECT_GT(specularInShadow, 50u);  // the light's highlight lies in the shadow: specular goes too
}

// ---- plumbing ---------------------------------------------------------------------------------------

// No light casts shadows: nothing is built, no draw points at shadows (the shaders skip the test
// entirely). One that does: the BVH, the SceneShadows with its method and ε, every draw pointing at it;
// a shadow map light: no BVH. Breaks if prepareShadows builds the BVH unconditionally or for any
// shadowing light, or forgets to point a draw at the shadows.
TEST_F(ShadowTest, BvhIsBuiltOnlyForAShadowingLight) {
    const AnalyticShadowScene scene = floatingSquare();
    for (const char* none : {"", "\"none\"", "false"}) {
        SCOPED_TRACE(none);
        const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, none)));
        EXPECT_EQ(prepared.shadows, nullptr);
        for (const PreparedDraw& d : prepared.draws)
            EXPECT_EQ(d.uniforms.shadows, nullptr);
    }
    for (const char* ray : {"\"ray\"", "true"}) {
        SCOPED_TRACE(ray);
        const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, ray)));
        ASSERT_NE(prepared.shadows, nullptr);
        ASSERT_NE(prepared.shadows->rays, nullptr);
        const SceneShadows& forShaders = prepared.shadows->forShaders;
        EXPECT_EQ(forShaders.rays, prepared.shadows->rays.get());
        EXPECT_EQ(forShaders.lights[0].method, ShadowMethod::Ray);
        EXPECT_EQ(forShaders.lights[1].method, ShadowMethod::None);
        EXPECT_FLOAT_EQ(forShaders.rayOffset, kShadowRayOffset * prepared.sceneExtent);
        EXPECT_GT(forShaders.rayOffset, 0.0f);
        EXPECT_EQ(prepared.shadows->rays->stats().triangles, 4u);  // the ground's two and the quad's two
        ASSERT_EQ(prepared.draws.size(), 2u);
        for (const PreparedDraw& d : prepared.draws)
            EXPECT_EQ(d.uniforms.shadows, &forShaders);
    }
    // A shadow map needs no BVH.
    const PreparedScene mapped = prepareScene(loadScene(writeScene(scene, "\"map\"")));
    ASSERT_NE(mapped.shadows, nullptr);
    EXPECT_EQ(mapped.shadows->rays, nullptr);
    EXPECT_EQ(mapped.shadows->forShaders.rays, nullptr);
    EXPECT_EQ(mapped.shadows->forShaders.lights[0].method, ShadowMethod::Map);
    EXPECT_EQ(mapped.draws[0].uniforms.shadows, &mapped.shadows->forShaders);
}

// The command line's --shadows (Scene::shadows) overrides every light's, the default light's too when
// the file has none: that light then casts the square's shadow onto the ground (some ground pixels
// darker than without). And --shadows none turns a file's "ray" off. Breaks if the default light is
// left out of the methods (it is added after the file's lights are read), or Scene::shadows is ignored.
TEST_F(ShadowTest, CommandLineShadowsReachEveryLightTheDefaultOneToo) {
    const AnalyticShadowScene scene = floatingSquare();
    Scene noLights = loadScene(writeScene(scene, "no light"));
    const LinearImage unshadowed = render(prepareScene(noLights));
    noLights.shadows = ShadowMethod::Ray;
    const PreparedScene prepared = prepareScene(noLights);
    EXPECT_EQ(prepared.shadowMethods[0], ShadowMethod::Ray);
    ASSERT_NE(prepared.shadows, nullptr);
    ASSERT_NE(prepared.shadows->rays, nullptr);
    const LinearImage shadowed = render(prepared);
    std::size_t darker = 0;
    for (std::size_t i = 0; i < shadowed.pixels.size(); ++i)
        darker += brightness(shadowed.pixels[i]) < 0.8 * brightness(unshadowed.pixels[i]);
    EXPECT_GT(darker, 200u);

    Scene rayInFile = loadScene(writeScene(scene, "\"ray\""));
    rayInFile.shadows = ShadowMethod::None;
    const PreparedScene off = prepareScene(rayInFile);
    EXPECT_EQ(off.shadows, nullptr);
}

// ---- robustness -------------------------------------------------------------------------------------

// Degenerate triangles in the quad's model (a repeated corner, three corners on a line, a sliver of
// zero area) change nothing: the shadow is still exactly the square's. Breaks if such a triangle
// upsets the BVH (Embree's robust mode is meant to take them) or the renderer drops the model.
TEST_F(ShadowTest, DegenerateTrianglesLeaveTheShadowExact) {
    const AnalyticShadowScene scene = floatingSquare();
    const std::string degenerate = "f 1 1 2\nf 1 2 1\nf 3 3 3\nv " + std::to_string(scene.quad[0].x) + " " +
                                   std::to_string(scene.quad[0].y) + " " + std::to_string(scene.quad[0].z) +
                                   "\nf 1 5 2\n";
    const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"", degenerate)));
    ASSERT_NE(prepared.shadows, nullptr);
    ASSERT_NE(prepared.shadows->rays, nullptr);
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    EXPECT_EQ(shadowDisagreements(render(prepared), pixels, darkLitThreshold(prepared, pixels)), 0u);
}

// A draw holding triangles with a NaN and an infinite corner (as a model scaled past the float range
// gives in eye space) before the BVH is built: they are counted and left out, the frame renders, and
// the square's shadow is still exact. Breaks if a non-finite corner reaches Embree (the BVH's bounds
// become NaN: rays miss everything or Embree fails) or the renderer gives up on the frame.
TEST_F(ShadowTest, NonFiniteTrianglesAreLeftOutOfTheBvhAndTheShadowStays) {
    const AnalyticShadowScene scene = floatingSquare();
    PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    ASSERT_EQ(prepared.draws.size(), 2u);
    std::vector<DrawTriangles> triangles;
    for (const PreparedDraw& d : prepared.draws)
        triangles.push_back({{d.vertices.begin(), d.vertices.end()}, {d.indices.begin(), d.indices.end()}});
    DrawTriangles& quad = triangles[1];
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const vec3 bad : {vec3(nan, 0, 0), vec3(0, inf, 0), vec3(-inf, nan, 1e30f)}) {
        const auto first = static_cast<std::uint32_t>(quad.vertices.size());
        MeshVertex corner = quad.vertices[0];
        quad.vertices.push_back(corner);
        corner.position = bad;
        quad.vertices.push_back(corner);
        corner = quad.vertices[2];
        quad.vertices.push_back(corner);
        quad.indices.insert(quad.indices.end(), {first, first + 1, first + 2});
    }
    setTriangles(prepared, std::move(triangles));
    prepareShadows(prepared);
    ASSERT_NE(prepared.shadows, nullptr);
    ASSERT_NE(prepared.shadows->rays, nullptr);
    EXPECT_EQ(prepared.shadows->rays->stats().nonFiniteSkipped, 3u);
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    const LinearImage image = render(prepared);
    std::size_t covered = 0;
    for (const vec4& pixel : image.pixels)
        covered += pixel != prepared.clearColor;
    EXPECT_EQ(covered, image.pixels.size());  // the ground fills the frame
    EXPECT_EQ(shadowDisagreements(image, pixels, darkLitThreshold(prepared, pixels)), 0u);
}

// ---- turntable ----------------------------------------------------------------------------------------

// Turned on the turntable, the square's shadow is where the turned square's corners project: the BVH
// is rebuilt from the objects as placed now. Turning back gives the first image again. Breaks if
// setTurntable does not rebuild the shadows (the shadow stays where the square was).
TEST_F(ShadowTest, TurntableMovesTheShadowWithTheObjects) {
    const AnalyticShadowScene scene = floatingSquare();
    PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const LinearImage first = render(prepared);
    for (const float degrees : {90.0f, 200.0f}) {
        SCOPED_TRACE(degrees);
        setTurntable(prepared, degrees);
        ASSERT_NE(prepared.shadows, nullptr);
        ASSERT_NE(prepared.shadows->rays, nullptr);
        AnalyticShadowScene turned = scene;
        const glm::dvec3 c(prepared.turntableCentre);
        const glm::dmat4 turn =
            glm::translate(glm::dmat4(1.0), c) *
            glm::rotate(glm::dmat4(1.0), glm::radians(double(degrees)), glm::dvec3(0, 1, 0)) *
            glm::translate(glm::dmat4(1.0), -c);
        for (glm::dvec3& corner : turned.quad)
            corner = glm::dvec3(turn * glm::dvec4(corner, 1.0));
        const std::vector<GroundPixel> pixels = checkedPixels(turned, prepared);
        EXPECT_EQ(shadowDisagreements(render(prepared), pixels, darkLitThreshold(prepared, pixels)), 0u);
    }
    setTurntable(prepared, 0.0f);
    EXPECT_EQ(render(prepared).pixels, first.pixels);
}

}  // namespace
}  // namespace facet
