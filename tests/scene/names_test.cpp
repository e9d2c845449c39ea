// The name tables (pipeline/names.h): every value of each enum has exactly one name, no two values
// share one, and parsing a value's name gives the value back.
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "pipeline/names.h"
#include "pipeline/state.h"
#include "scene/scene.h"
#include "shading/fog.h"
#include "shading/gamma.h"
#include "shading/lighting.h"

namespace facet {
namespace {

// `values` is every value of E, written out here: the table must name each once and nothing else.
template <class E>
void expectOneNameEach(const std::vector<E>& values) {
    const auto table = enumNames(E{});
    EXPECT_EQ(table.size(), values.size()) << "a value without a name, or one named twice";
    std::set<std::string_view> names;
    for (const EnumName<E>& entry : table) {
        EXPECT_FALSE(entry.name.empty());
        EXPECT_TRUE(names.insert(entry.name).second) << "two values named " << entry.name;
    }
    for (const E value : values) {
        int rows = 0;
        for (const EnumName<E>& entry : table)
            rows += entry.value == value;
        EXPECT_EQ(rows, 1) << "value " << static_cast<int>(value) << " has " << rows << " names";
        const std::string_view name = nameOf(value);
        ASSERT_TRUE(parseName<E>(name).has_value()) << name;
        EXPECT_EQ(*parseName<E>(name), value) << name;
    }
    EXPECT_FALSE(parseName<E>("no-such-name").has_value());
}

TEST(NameTables, PipelineStateEnums) {
    expectOneNameEach<CullMode>({CullMode::None, CullMode::Back, CullMode::Front});
    expectOneNameEach<FrontFace>({FrontFace::CounterClockwise, FrontFace::Clockwise});
    expectOneNameEach<CompareOp>({CompareOp::Never, CompareOp::Less, CompareOp::Equal, CompareOp::LessEqual,
                                  CompareOp::Greater, CompareOp::NotEqual, CompareOp::GreaterEqual,
                                  CompareOp::Always});
    expectOneNameEach<Interpolation>({Interpolation::PerspectiveCorrect, Interpolation::Affine});
    expectOneNameEach<BlendMode>({BlendMode::Replace, BlendMode::Additive, BlendMode::Over,
                                  BlendMode::PremultipliedOver, BlendMode::Multiply, BlendMode::OverGL});
    expectOneNameEach<ProvokingVertex>({ProvokingVertex::Last, ProvokingVertex::First});
    expectOneNameEach<FragmentOutput>({FragmentOutput::Blend, FragmentOutput::AppendToLists});
    expectOneNameEach<FragmentFate>({FragmentFate::Written, FragmentFate::DepthFailed,
                                     FragmentFate::Discarded, FragmentFate::Stored, FragmentFate::Dropped});
    expectOneNameEach<TriangleFate>({TriangleFate::Drawn, TriangleFate::NonFinite,
                                     TriangleFate::OutsideFrustum, TriangleFate::ClippedAway,
                                     TriangleFate::ZeroArea, TriangleFate::MissesSamples,
                                     TriangleFate::Culled});
}

TEST(NameTables, LightingEnums) {
    expectOneNameEach<ReflectionModel>(
        {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance});
    expectOneNameEach<ShadingFrequency>({ShadingFrequency::Constant, ShadingFrequency::Flat,
                                         ShadingFrequency::Gouraud, ShadingFrequency::Phong});
    expectOneNameEach<LightKind>(
        {LightKind::Directional, LightKind::Point, LightKind::Spot, LightKind::Rect, LightKind::Disk});
    expectOneNameEach<SpotProfile>({SpotProfile::OpenGL, SpotProfile::Smooth});
    expectOneNameEach<RangeWindow>({RangeWindow::Ue4, RangeWindow::Jc2});
    expectOneNameEach<NormalDistribution>(
        {NormalDistribution::Beckmann, NormalDistribution::GGX, NormalDistribution::Gaussian});
    expectOneNameEach<FresnelModel>({FresnelModel::Schlick, FresnelModel::Exact});
    expectOneNameEach<GeometryTerm>({GeometryTerm::CookTorrance, GeometryTerm::SmithGGX});
    expectOneNameEach<VertexNormals>(
        {VertexNormals::TriangleArea, VertexNormals::PolygonArea, VertexNormals::Angle});
    expectOneNameEach<MathPrecision>({MathPrecision::Exact, MathPrecision::Fast});
    expectOneNameEach<Normalization>({Normalization::Exact, Normalization::Fast});
}

TEST(NameTables, FogGammaAndSceneEnums) {
    expectOneNameEach<FogMode>(
        {FogMode::None, FogMode::Linear, FogMode::Exponential, FogMode::ExponentialSquared, FogMode::Height});
    expectOneNameEach<FogDistance>({FogDistance::EyeDepth, FogDistance::Radial});
    expectOneNameEach<TransferCurve>({TransferCurve::Srgb, TransferCurve::Power, TransferCurve::Linear});
    expectOneNameEach<LightingPreset>({LightingPreset::Facet, LightingPreset::GL, LightingPreset::Lecture});
    expectOneNameEach<TransparencyMode>(
        {TransparencyMode::Sorted, TransparencyMode::Unsorted, TransparencyMode::Exact});
    expectOneNameEach<SortKey>({SortKey::Centroid, SortKey::FarthestVertex});
}

// The printers print the table's name.
TEST(NameTables, PrintersUseTheTable) {
    DrawState state;
    state.raster.cull = CullMode::Front;
    state.blend = BlendMode::PremultipliedOver;
    std::ostringstream text;
    text << state;
    EXPECT_NE(text.str().find("cull " + std::string(nameOf(CullMode::Front))), std::string::npos)
        << text.str();
    EXPECT_NE(text.str().find("blend " + std::string(nameOf(BlendMode::PremultipliedOver))),
              std::string::npos)
        << text.str();
}

}  // namespace
}  // namespace facet
