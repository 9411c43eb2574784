// Graftal description files: the shipped ones load with what they promise, each broken file is
// refused with its key named, and the reference documents every key.
#include "pipeline/input/graftal_io.h"

#include <gtest/gtest.h>

#include "pipeline/input/error.h"
#include "pipeline/input/presets.h"
#include "test_util.h"

namespace pleinair {
namespace {

// The problems of a description as one string ("" when it parses), its source "g.json".
std::string problem(const std::string& text, const std::vector<std::string>& set = {}) {
    try {
        parse_graftal(text, "g.json", set);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A valid description with one example of one primitive of type `type` over four vertices;
// `extra` is spliced into the primitive, `top` into the file.
std::string with(const std::string& primitive, const std::string& top = "") {
    return R"({)" + top + R"("examples": [{"name": "leaf",
        "vertices": [[0, 0, 0], [0.2, 0.5, 0], [0, 1, 0], [-0.2, 0.5, 0]],
        "primitives": [)" +
           primitive + R"(]}]})";
}

const std::string kPolygon = R"({"type": "polygon", "vertices": [0, 1, 2, 3], "color": "#3f7a2a"})";

TEST(GraftalFiles, TheShippedOnesLoadWithTheirLooks) {
    const auto names = preset_names("graftals");
    for (const char* want : {"seuss-leaf-tuft", "grass-tuft", "corot-leaf"})
        EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        const GraftalDesc g = load_graftal(name);
        EXPECT_FALSE(g.description.empty());
        ASSERT_FALSE(g.examples.empty());
        ASSERT_FALSE(g.tuft.levels.empty());
        EXPECT_EQ(g.tuft.levels[0].lambda, 0.0f);
        for (const GraftalExample& e : g.examples)
            for (const GraftalPrimitive& p : e.primitives) {
                ASSERT_FALSE(p.vertices.empty());
                for (uint32_t v : p.vertices) EXPECT_LT(v, e.vertices.size());
                if (p.type == PrimitiveType::kStroke) {
                    EXPECT_EQ(p.widths.size(), p.vertices.size());
                }
            }
    }
    const GraftalDesc seuss = load_graftal("seuss-leaf-tuft");
    EXPECT_EQ(seuss.tuft.levels.size(), 3u);
    EXPECT_EQ(seuss.lambda, GraftalLambda::kTauRhoSigma);
    EXPECT_EQ(seuss.rho, GraftalRho::kSilhouette);
    const GraftalDesc grass = load_graftal("grass-tuft");
    EXPECT_EQ(grass.rho, GraftalRho::kFrontFacing);
    EXPECT_EQ(grass.placement, GraftalPlacement::kDensity);
    // Colours are read as sRGB and kept linear: #4f7a2b's green 0x7a = 122 is 0.195 linear.
    EXPECT_NEAR(grass.examples[0].primitives[0].color.g, 0.1946f, 1e-3f);
    const GraftalDesc corot = load_graftal("corot-leaf");
    EXPECT_EQ(corot.every_k, 1);  // a dab at every leaf, as the strokes have
    EXPECT_GT(corot.light, 0.0f);
}

TEST(GraftalFiles, DefaultsForWhatAFileLeavesOut) {
    const GraftalDesc g = parse_graftal(with(kPolygon), "g.json");
    EXPECT_EQ(g.frame, GraftalFrame::kView);
    EXPECT_EQ(g.tuft.levels.size(), 1u);  // no tuft: a single graftal, always drawn
    EXPECT_EQ(g.examples[0].extent_to, glm::vec3(0, 1, 0));
    EXPECT_EQ(g.examples[0].primitives[0].vertices, (std::vector<uint32_t>{0, 1, 2, 3}));
}

TEST(GraftalFiles, BrokenFilesNameTheKeyAndWhatWasExpected) {
    const struct {
        std::string text, want;
    } cases[] = {
        {with(kPolygon, R"("lamda": "sigma", )"),
         "g.json: /lamda: unknown key (did you mean \"lambda\"?)"},
        {with(kPolygon, R"("rho": "edges", )"),
         "g.json: /rho: expected \"silhouette\", \"front\" or \"none\", got \"edges\""},
        {with(kPolygon, R"("preferred_size_px": 0, )"),
         "g.json: /preferred_size_px: must be in [0.5, 4096], got 0"},
        {with(R"({"type": "polygon", "vertices": [0, 1, 9]})"),
         "g.json: /examples/0/primitives/0/vertices/2: expected an index of the example's "
         "vertices (0 to 3), got 9"},
        {with(R"({"type": "polygon", "vertices": [0, 1]})"),
         "g.json: /examples/0/primitives/0/vertices: expected a list of at least 3 numbers, got "
         "[0,1]"},
        {with(R"({"type": "stroke", "vertices": [0, 1, 2], "widths": [0.1, 0]})"),
         "g.json: /examples/0/primitives/0/widths: expected 3 widths (one per vertex), got 2"},
        {with(R"({"type": "stroke", "vertices": [0, 2]})"),
         "g.json: /examples/0/primitives/0/widths: missing: a stroke's width at each vertex"},
        {with(R"({"type": "fan", "vertices": [0, 1, 2], "widths": [1, 1, 1]})"),
         "g.json: /examples/0/primitives/0/widths: only a stroke has widths"},
        {with(R"({"type": "blob", "vertices": [0, 1, 2]})"),
         "g.json: /examples/0/primitives/0/type: expected \"stroke\", \"strip\", \"fan\" or "
         "\"polygon\", got \"blob\""},
        {with(R"({"vertices": [0, 1, 2]})"),
         "g.json: /examples/0/primitives/0/type: missing: this key is required"},
        {with(R"({"type": "polygon", "vertices": [0, 1, 2], "lod": {"size": {}}})"),
         "g.json: /examples/0/primitives/0/lod/size: unknown key (a primitive ramps \"width\", "
         "\"length\" or \"opacity\" with λ)"},
        {with(R"({"type": "polygon", "vertices": [0, 1, 2],
                  "lod": {"opacity": {"lambda": [3, 1], "from": 0, "to": 1}}})"),
         "g.json: /examples/0/primitives/0/lod/opacity/lambda: expected [a, b] with 0 <= a <= b "
         "<= 1e6, got [3,1]"},
        {with(kPolygon, R"("tuft": {"levels": [{"lambda": 1}]}, )"),
         "g.json: /tuft/levels/0/lambda: the first level's λ must be 0 (it is always drawn), got "
         "1"},
        {with(kPolygon, R"("tuft": {"levels": [{"lambda": 0}, {"lambda": 2}, {"lambda": 2}]}, )"),
         "g.json: /tuft/levels/2/lambda: must be greater than the previous level's (2), got 2"},
        {with(kPolygon, R"("tuft": {"levels": [{"lambda": 0, "examples": ["leaf", "twig"]}]}, )"),
         "g.json: /tuft/levels/0/examples/1: expected the name of one of the examples, got "
         "\"twig\""},
        {with(kPolygon, R"("tuft": {"hysteresis": 0.5}, )"),
         "g.json: /tuft/hysteresis: must be in [0, 0.49], got 0.5"},
        {R"({"description": "nothing to draw"})",
         "g.json: /examples: missing: a list of example graftals"},
        {R"({"examples": [{"name": "a", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
            "primitives": [{"type": "fan", "vertices": [0, 1, 2]}]},
            {"name": "a", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
            "primitives": [{"type": "fan", "vertices": [0, 1, 2]}]}]})",
         "g.json: /examples/1/name: \"a\" names two examples"},
        {R"({"examples": [{"name": "a", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1e9, 0]],
            "extent": [[0, 0, 0], [0, 0, 0]],
            "primitives": [{"type": "fan", "vertices": [0, 1, 2]}]}]})",
         "g.json: /examples/0/vertices/2: each coordinate must be in [-100, 100], got "
         "[0,1000000000.0,0]\n"
         "g.json: /examples/0/extent: expected two different points [[x, y, z], [x, y, z]] (the "
         "graftal's canonical length)"},
        {R"({"examples": [{"name": "a", "vertices": [[0, 0, 0]], "primitives": []}]})",
         "g.json: /examples/0/primitives: expected a non-empty list of drawing primitives"},
    };
    for (const auto& c : cases) EXPECT_EQ(problem(c.text), c.want) << c.text;
}

TEST(GraftalFiles, SetOverridesAKeyAndIsNamedWhenWrong) {
    const GraftalDesc g = parse_graftal(with(kPolygon), "g.json", {"/tuft/queue=3"});
    EXPECT_EQ(g.tuft.queue, 3);
    EXPECT_EQ(problem(with(kPolygon), {"/tuft/queue=0"}),
              "g.json: /tuft/queue: must be in [1, 240], got 0 (set by --set)");
}

TEST(GraftalFiles, TheReferenceDocumentsEveryKey) {
    const std::string ref = graftal_reference();
    for (const char* key : {"/frame",
                            "/rho",
                            "/lambda",
                            "/preferred_size_px",
                            "/length",
                            "/alpha_from_rho",
                            "placement/at",
                            "placement/every_k",
                            "placement/per_area",
                            "variation/angle",
                            "tuft/queue",
                            "tuft/hysteresis",
                            "tuft/transition_seconds",
                            "tuft/grow_from",
                            "tuft/spread",
                            "tuft/levels/N/lambda",
                            "tuft/levels/N/count",
                            "tuft/levels/N/examples",
                            "examples/N/vertices",
                            "examples/N/extent",
                            "primitives/N/type",
                            "primitives/N/widths",
                            "outline/width",
                            "/lambda"})
        EXPECT_NE(ref.find(key), std::string::npos) << key;
}

TEST(GraftalFiles, PresetsListsThemAndAMissingOneNamesWhatThereIs) {
    const auto r = test::run_pleinair("presets");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("graftal  grass-tuft"), std::string::npos) << r.out;
    try {
        load_graftal("truffula", "s.json", "/families/oak/graftal");
        ADD_FAILURE() << "loaded a graftal that does not exist";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("s.json: /families/oak/graftal: no graftal preset "
                                             "\"truffula\""),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace pleinair
