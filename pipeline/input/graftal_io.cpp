// The graftal description's key table (each key documented where it is read) and its checks:
// primitives that index existing vertices, strokes with a width per vertex, tuft levels from
// λ = 0 upwards, examples named once and named right.
#include "pipeline/input/graftal_io.h"

#include <set>

#include "pipeline/input/json_visitors.h"
#include "pipeline/input/presets.h"
#include "shading/color.h"

namespace pleinair {

using namespace json_detail;

namespace {

const std::pair<GraftalFrame, const char*> kFrames[] = {{GraftalFrame::kView, "view"},
                                                        {GraftalFrame::kUpright, "upright"},
                                                        {GraftalFrame::kSurface, "surface"}};
const std::pair<GraftalRho, const char*> kRhos[] = {{GraftalRho::kSilhouette, "silhouette"},
                                                    {GraftalRho::kFrontFacing, "front"},
                                                    {GraftalRho::kNone, "none"}};
const std::pair<GraftalLambda, const char*> kLambdas[] = {
    {GraftalLambda::kRhoSigma, "rho_sigma"},
    {GraftalLambda::kTauRhoSigma, "tau_rho_sigma"},
    {GraftalLambda::kSigma, "sigma"}};
const std::pair<GraftalPlacement, const char*> kPlacements[] = {
    {GraftalPlacement::kLeafParticles, "leaf_particles"},
    {GraftalPlacement::kVertices, "vertices"},
    {GraftalPlacement::kFaces, "faces"},
    {GraftalPlacement::kEveryKthFace, "every_kth_face"},
    {GraftalPlacement::kDensity, "density"},
    {GraftalPlacement::kDifference, "difference_image"}};
const std::pair<PrimitiveType, const char*> kPrimitiveTypes[] = {
    {PrimitiveType::kStroke, "stroke"},
    {PrimitiveType::kStrip, "strip"},
    {PrimitiveType::kFan, "fan"},
    {PrimitiveType::kPolygon, "polygon"}};

// G is GraftalDesc or const GraftalDesc.
template <class G, class V>
void visit_graftal(G& g, V& v) {
    v.text("description", g.description, "What the graftal depicts, for `pleinair presets`.");
    v.choice("frame", g.frame, kFrames,
             "Local frame (file 000 §2.2.1): \"view\" x = n x v turns to the viewer, \"upright\" "
             "x = n x (n x up) hangs whatever the view, \"surface\" follows the surface.");
    v.choice("rho", g.rho, kRhos,
             "Orientation term ρ: \"silhouette\" 1 - abs(n.v) (detail where the surface turns "
             "away), \"front\" abs(n.v) (detail on surfaces facing the viewer), \"none\" 1.");
    v.choice("lambda", g.lambda, kLambdas,
             "Level of detail λ from σ (size), ρ and τ (transition): ρσ, τρσ (primitives fade "
             "in with the graftal) or σ.");
    v.real("preferred_size_px", g.preferred_size_px, {0.5, 4096}, "px",
           "Screen size at which σ = 1 (the paper's 25-pixel leaf): larger on screen draws more.");
    v.real("length", g.length, {1e-4, 1000}, "world units",
           "World length of a graftal whose canonical extent is 1.");
    v.boolean("alpha_from_rho", g.alpha_from_rho,
              "Opacity = ρ (file 001): graftals fade away from silhouettes.");
    v.real("light", g.light, {0, 0.9}, "",
           "How much the sun shades a graftal: colours x (1 - light + light x max(0, n.l)), so "
           "the side away from the sun darkens but never goes black; 0 draws flat colour.");
    v.object("placement", "Where graftals are placed (file 000 §2.2.2, file 004)", [&] {
        v.choice("at", g.placement, kPlacements,
                 "At leaf particles, mesh vertices, faces, every k-th face, at a density per "
                 "area, or by the difference image each frame.");
        v.integer("every_k", g.every_k, {1, 1000000},
                  "For \"every_kth_face\": one face in k; for \"leaf_particles\": one particle "
                  "in k (a crown has thousands).");
        v.real("per_area", g.per_area, {1e-6, 1e6}, "1/world unit²",
               "For \"density\": graftals per square world unit; for \"difference_image\" on "
               "a material, its candidates' density (on a family, every leaf is a candidate).");
        v.integer("cell_px", g.cell_px, {1, 64},
                  "For \"difference_image\": pixels a side of the desire image's cells.");
        v.integer("dot_cells", g.dot_cells, {1, 61},
                  "For \"difference_image\": cells across the blurred dot a tuft subtracts (a "
                  "row of Pascal's triangle); larger spaces tufts further apart.");
        v.real("threshold", g.threshold, {0.001, 1}, "",
               "For \"difference_image\": desire left where a tuft stands, at least this.");
        v.real("band", g.band, {0, 1}, "",
               "For \"difference_image\": a tuft's opacity eases from 0 at the threshold to 1 "
               "this much above it, and it takes that share of its dot, so tufts fade in and "
               "out as the view moves instead of popping; 0 places them whole.");
    });
    v.object("variation", "How copies differ from their example, drawn by the seed", [&] {
        v.real("length", g.variation.length, {0, 0.95}, "", "Length scale 1 ± this.");
        v.real("width", g.variation.width, {0, 0.95}, "", "Width scale 1 ± this.");
        v.real("angle", g.variation.angle, {0, 180}, "degrees", "Turn about the normal, ± this.");
        v.real("color", g.variation.color, {0, 0.95}, "", "Lightness scale 1 ± this.");
    });
    v.object("tuft", "Levels of a multi-level tuft (file 000 §2.3)", [&] {
        v.integer("queue", g.tuft.queue, {1, 240},
                  "Frames of level choices averaged before the hysteresis (the paper's LIFO "
                  "queue).");
        v.real("hysteresis", g.tuft.hysteresis, {0, 0.49}, "levels",
               "Past the half-way point a level change needs: 0.25 moves up at i + 0.75 and down "
               "below i - 0.75, as in the paper.");
        v.real("transition_seconds", g.tuft.transition_seconds, {0, 60}, "s",
               "Time a level takes to grow in or fade out (τ from 0 to 1 or back).");
        v.real("grow_from", g.tuft.grow_from, {0, 1}, "",
               "Scale of a graftal at τ = 0: it grows from this to full size.");
        v.real("spread", g.tuft.spread, {0, 10}, "graftal lengths",
               "How far from the tuft's base its added graftals sit.");
        v.claim("levels");  // a list, read by parse_graftal
    });
    v.claim("examples");  // a list, read by parse_graftal
}

template <class P, class V>
void visit_primitive(P& p, V& v) {
    v.choice("type", p.type, kPrimitiveTypes,
             "A \"stroke\" (a path with a width per vertex), a triangle \"strip\" or \"fan\", or a "
             "filled \"polygon\".");
    v.color("color", p.color, "Fill colour.");
    v.real("opacity", p.opacity, {0, 1}, "", "Opacity of the fill.");
    v.object("outline", "An outline around the primitive (polygons and strokes)", [&] {
        v.color("color", p.outline_color, "Outline colour.");
        v.real("width", p.outline_width, {0, 10}, "canonical units", "0: no outline.");
    });
    v.claim("vertices");  // indices, read by parse_graftal
    v.claim("widths");
    v.claim("lod");
}

template <class L, class V>
void visit_ramp(L& r, V& v) {
    v.real("from", r.at_start, {0, 10}, "", "Multiplier at and below the ramp's first λ.");
    v.real("to", r.at_end, {0, 10}, "", "Multiplier at and above its last λ.");
    v.claim("lambda");  // [first, last], read by read_ramp
}

template <class L, class V>
void visit_level(L& l, V& v) {
    v.real("lambda", l.lambda, {0, 1e6}, "",
           "λ_i: the tuft reaches this level once its λ is at least this (the first level's is "
           "0).");
    v.integer("count", l.count, {1, 1000}, "Graftals this level adds.");
    v.claim("examples");  // names, read by parse_graftal
}

// A list of numbers under `key` (absent: `out` unchanged).
bool read_numbers(const json& obj, const char* key, const std::string& ptr, size_t min_size,
                  std::vector<double>& out, std::vector<Problem>& problems) {
    auto it = obj.find(key);
    if (it == obj.end()) return false;
    if (!it->is_array() || it->size() < min_size) {
        problems.push_back({ptr, "expected a list of at least " + std::to_string(min_size) +
                                     " numbers, got " + describe(*it)});
        return false;
    }
    out.clear();
    for (size_t i = 0; i < it->size(); ++i) {
        if (!(*it)[i].is_number()) {
            problems.push_back(
                {ptr + "/" + std::to_string(i), "expected a number, got " + describe((*it)[i])});
            return false;
        }
        out.push_back((*it)[i].get<double>());
    }
    return true;
}

// "vertices": [[x, y, z], ...], every coordinate within +-100 canonical units.
void read_points(const json& obj, const char* key, const std::string& ptr,
                 std::vector<glm::vec3>& out, std::vector<Problem>& problems) {
    auto it = obj.find(key);
    if (it == obj.end()) return problems.push_back({ptr, "missing: a list of [x, y, z] points"});
    if (!it->is_array() || it->empty() || it->size() > 4096)
        return problems.push_back(
            {ptr, "expected a list of 1 to 4096 points [x, y, z], got " + describe(*it)});
    for (size_t i = 0; i < it->size(); ++i) {
        const json& p = (*it)[i];
        const std::string at = ptr + "/" + std::to_string(i);
        if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() ||
            !p[2].is_number()) {
            problems.push_back({at, "expected three numbers [x, y, z], got " + describe(p)});
            continue;
        }
        const glm::dvec3 d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
        if (!(std::abs(d.x) <= 100 && std::abs(d.y) <= 100 && std::abs(d.z) <= 100)) {
            problems.push_back({at, "each coordinate must be in [-100, 100], got " + describe(p)});
            continue;
        }
        out.push_back(glm::vec3(d));
    }
}

void read_ramp(const json& lod, const char* key, const std::string& ptr, LodRamp& ramp,
               std::vector<Problem>& problems, std::set<std::string>& plain) {
    auto it = lod.find(key);
    if (it == lod.end()) return;
    const std::string at = ptr + "/" + key;
    if (!it->is_object())
        return problems.push_back(
            {at, "expected {\"lambda\": [a, b], \"from\": x, \"to\": y}, got " + describe(*it)});
    Reader r(*it, problems, plain, at);
    visit_ramp(ramp, r);
    r.finish();
    std::vector<double> range;
    if (!it->contains("lambda")) {
        problems.push_back({at + "/lambda", "missing: [a, b], the λ over which the ramp runs"});
    } else if (read_numbers(*it, "lambda", at + "/lambda", 2, range, problems)) {
        if (range.size() != 2 || !(range[0] >= 0 && range[0] <= range[1] && range[1] <= 1e6))
            problems.push_back({at + "/lambda", "expected [a, b] with 0 <= a <= b <= 1e6, got " +
                                                    describe((*it)["lambda"])});
        else
            ramp.lambda_from = static_cast<float>(range[0]),
            ramp.lambda_to = static_cast<float>(range[1]);
    }
}

void read_primitive(const json& j, Reader& r, const std::string& ptr, size_t vertex_count,
                    bool vertices_ok, GraftalPrimitive& p, std::vector<Problem>& problems,
                    std::set<std::string>& plain) {
    r.require("type");
    visit_primitive(p, r);
    // Without a known type the counts below cannot be checked: say only what is wrong.
    bool typed = false;
    if (auto t = j.find("type"); t != j.end() && t->is_string())
        for (const auto& [value, name] : kPrimitiveTypes)
            typed |= t->get_ref<const std::string&>() == name;
    if (!typed) return;
    p.color = srgb_to_linear(p.color);
    p.outline_color = srgb_to_linear(p.outline_color);
    // Vertices: indices into the example's canonical points, enough of them for the type.
    const size_t need = p.type == PrimitiveType::kStroke ? 2 : 3;
    std::vector<double> idx;
    if (!j.contains("vertices"))
        problems.push_back({ptr + "/vertices", "missing: the indices of the example's vertices"});
    else if (read_numbers(j, "vertices", ptr + "/vertices", need, idx, problems) && vertices_ok)
        for (size_t i = 0; i < idx.size(); ++i) {
            if (!(idx[i] >= 0 && idx[i] < static_cast<double>(vertex_count)) ||
                idx[i] != std::floor(idx[i])) {
                problems.push_back({ptr + "/vertices/" + std::to_string(i),
                                    "expected an index of the example's vertices (0 to " +
                                        std::to_string(vertex_count - 1) + "), got " +
                                        format_number(idx[i])});
                continue;
            }
            p.vertices.push_back(static_cast<uint32_t>(idx[i]));
        }
    std::vector<double> widths;
    if (p.type == PrimitiveType::kStroke) {
        if (!j.contains("widths"))
            problems.push_back({ptr + "/widths", "missing: a stroke's width at each vertex"});
        else if (read_numbers(j, "widths", ptr + "/widths", 2, widths, problems)) {
            if (widths.size() != idx.size())
                problems.push_back({ptr + "/widths", "expected " + std::to_string(idx.size()) +
                                                         " widths (one per vertex), got " +
                                                         std::to_string(widths.size())});
            for (size_t i = 0; i < widths.size(); ++i) {
                if (!(widths[i] >= 0 && widths[i] <= 10))
                    problems.push_back({ptr + "/widths/" + std::to_string(i),
                                        "must be in [0, 10], got " + format_number(widths[i])});
                p.widths.push_back(static_cast<float>(widths[i]));
            }
        }
    } else if (j.contains("widths")) {
        problems.push_back({ptr + "/widths", "only a stroke has widths"});
    }
    if (auto it = j.find("lod"); it != j.end()) {
        const std::string at = ptr + "/lod";
        if (!it->is_object()) {
            problems.push_back({at, "expected an object of ramps, got " + describe(*it)});
        } else {
            for (const auto& [k, x] : it->items())
                if (k != "width" && k != "length" && k != "opacity")
                    problems.push_back({at + "/" + pointer_token(k),
                                        "unknown key (a primitive ramps \"width\", \"length\" or "
                                        "\"opacity\" with λ)"});
            read_ramp(*it, "width", at, p.width_ramp, problems, plain);
            read_ramp(*it, "length", at, p.length_ramp, problems, plain);
            read_ramp(*it, "opacity", at, p.opacity_ramp, problems, plain);
        }
    }
}

void read_examples(const json& doc, GraftalDesc& g, std::vector<Problem>& problems,
                   std::set<std::string>& plain) {
    if (!doc.contains("examples"))
        return problems.push_back({"/examples", "missing: a list of example graftals"});
    if (!doc["examples"].is_array() || doc["examples"].empty())
        return problems.push_back(
            {"/examples",
             "expected a non-empty list of example graftals, got " + describe(doc["examples"])});
    std::set<std::string> names;
    read_list(doc, "examples", "/examples", problems, plain,
              [&](const json& j, Reader& r, const std::string& ptr) {
                  GraftalExample e;
                  r.require("name");
                  r.text("name", e.name, "");
                  if (j.contains("name") && e.name.empty())
                      problems.push_back({ptr + "/name", "must not be empty"});
                  else if (!e.name.empty() && !names.insert(e.name).second)
                      problems.push_back({ptr + "/name", "\"" + e.name + "\" names two examples"});
                  r.claim("vertices");
                  r.claim("primitives");
                  r.claim("extent");
                  const size_t before = problems.size();
                  read_points(j, "vertices", ptr + "/vertices", e.vertices, problems);
                  // Indices are checked only against a list read whole (no second error for one
                  // bad point).
                  const bool vertices_ok = problems.size() == before;
                  if (j.contains("extent")) {
                      std::vector<glm::vec3> ends;
                      read_points(j, "extent", ptr + "/extent", ends, problems);
                      if (ends.size() != 2 || ends[0] == ends[1])
                          problems.push_back({ptr + "/extent",
                                              "expected two different points [[x, y, z], [x, y, "
                                              "z]] (the graftal's canonical length)"});
                      else
                          e.extent_from = ends[0], e.extent_to = ends[1];
                  }
                  if (!j.contains("primitives") || !j["primitives"].is_array() ||
                      j["primitives"].empty()) {
                      problems.push_back(
                          {ptr + "/primitives", "expected a non-empty list of drawing primitives"});
                  } else {
                      read_list(j, "primitives", ptr + "/primitives", problems, plain,
                                [&](const json& pj, Reader& pr, const std::string& pptr) {
                                    GraftalPrimitive p;
                                    read_primitive(pj, pr, pptr, e.vertices.size(), vertices_ok, p,
                                                   problems, plain);
                                    e.primitives.push_back(std::move(p));
                                });
                  }
                  g.examples.push_back(std::move(e));
              });
}

void read_levels(const json& doc, GraftalDesc& g, std::vector<Problem>& problems,
                 std::set<std::string>& plain) {
    g.tuft.levels.clear();
    auto tuft = doc.find("tuft");
    if (tuft == doc.end() || !tuft->is_object() || !tuft->contains("levels")) {
        g.tuft.levels.push_back(TuftLevel{});  // a single graftal: one level, always in
        return;
    }
    const json& levels = (*tuft)["levels"];
    if (!levels.is_array() || levels.empty() || levels.size() > 16)
        return problems.push_back(
            {"/tuft/levels", "expected a list of 1 to 16 levels, got " + describe(levels)});
    read_list(
        *tuft, "levels", "/tuft/levels", problems, plain,
        [&](const json& j, Reader& r, const std::string& ptr) {
            TuftLevel l;
            r.require("lambda");
            visit_level(l, r);
            if (auto it = j.find("examples"); it != j.end()) {
                if (!it->is_array()) {
                    problems.push_back({ptr + "/examples",
                                        "expected a list of example names, got " + describe(*it)});
                } else {
                    for (size_t i = 0; i < it->size(); ++i) {
                        const json& n = (*it)[i];
                        bool known = false;
                        for (const GraftalExample& e : g.examples)
                            known |= n.is_string() && n.get_ref<const std::string&>() == e.name;
                        if (!known)
                            problems.push_back({ptr + "/examples/" + std::to_string(i),
                                                "expected the name of one of the "
                                                "examples, got " +
                                                    describe(n)});
                        else
                            l.examples.push_back(n.get<std::string>());
                    }
                }
            }
            const std::string at = ptr + "/lambda";
            if (g.tuft.levels.empty() && l.lambda != 0)
                problems.push_back({at,
                                    "the first level's λ must be 0 (it is always "
                                    "drawn), got " +
                                        format_number(l.lambda)});
            else if (!g.tuft.levels.empty() && !(l.lambda > g.tuft.levels.back().lambda))
                problems.push_back({at, "must be greater than the previous level's (" +
                                            format_number(g.tuft.levels.back().lambda) + "), got " +
                                            format_number(l.lambda)});
            g.tuft.levels.push_back(std::move(l));
        });
}

}  // namespace

GraftalDesc parse_graftal(const std::string& text, const std::string& source,
                          const std::vector<std::string>& overrides) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = parse_document(text, source, overrides, problems, overridden);
    GraftalDesc g;
    std::set<std::string> plain;
    if (doc.is_object()) {
        Reader reader(doc, problems, plain);
        visit_graftal(g, reader);
        reader.finish();
        read_examples(doc, g, problems, plain);
        read_levels(doc, g, problems, plain);
    }
    mark_overrides(problems, overridden);
    if (!problems.empty()) throw InputError(source, problems);
    return g;
}

GraftalDesc load_graftal(const std::string& name, const std::string& source,
                         const std::string& pointer) {
    auto file = resolve_preset("graftals", name, source.empty() ? "--graftal" : source, pointer);
    return parse_graftal(read_input_file(file), file.string());
}

std::string graftal_reference() {
    Documenter d;
    d.out << "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
    const GraftalDesc g;
    visit_graftal(g, d);
    d.note("tuft/levels", "[{\"lambda\": 0}]",
           "The tuft's levels, each an object of the keys below; none: a single graftal.");
    d.object("tuft/levels/N", "A level", [&] {
        const TuftLevel l;
        visit_level(l, d);
        d.note("examples", "[] (all)", "Names of the examples its graftals are drawn from.");
    });
    d.object("examples/N", "An example graftal", [&] {
        d.note("name", "required", "Its name, unique in the file.");
        d.note("vertices", "required",
               "Canonical points [x, y, z]: y along the surface normal, x across, in [-100, 100].");
        d.note("extent", "[[0, 0, 0], [0, 1, 0]]",
               "Two points whose distance is the canonical length (W at `length` 1).");
        d.object("primitives/N", "A drawing primitive", [&] {
            const GraftalPrimitive p;
            visit_primitive(p, d);
            d.note("vertices", "required",
                   "Indices of the example's vertices: a stroke's path (2 or more), a strip's or "
                   "fan's order, a polygon's boundary (3 or more).");
            d.note("widths", "required for strokes", "Full width at each vertex of the path.");
            d.object("lod/RAMP",
                     "A multiplier ramped with λ (file 000 §2.2.3); RAMP is width, length or "
                     "opacity",
                     [&] {
                         const LodRamp ramp;
                         visit_ramp(ramp, d);
                         d.note("lambda", "required", "[a, b]: the λ over which it runs.");
                     });
        });
    });
    return d.out.str();
}

}  // namespace pleinair
