// JSON reading, writing and documentation of TreeParams through the key table
// (visit_tree_params).
#include "pipeline/input/json_params.h"

#include "pipeline/input/json_visitors.h"

namespace pleinair {

using namespace json_detail;

TreeParams parse_tree_params(const std::string& text, const std::string& source,
                             const std::vector<std::string>& overrides) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = parse_document(text, source, overrides, problems, overridden);
    TreeParams params;
    std::set<std::string> plain;
    Reader reader(doc, problems, plain);
    visit_tree_params(params, reader);
    reader.finish();
    for (const auto& line : validate(params)) {
        auto colon = line.find(": ");
        std::string ptr = line.substr(0, colon);
        // A plain number stands for {"base": x}; name the key the file actually has.
        if (ptr.size() > 5 && ptr.ends_with("/base") && plain.count(ptr.substr(0, ptr.size() - 5)))
            ptr.resize(ptr.size() - 5);
        problems.push_back({ptr, line.substr(colon + 2)});
    }
    mark_overrides(problems, overridden);
    if (!problems.empty()) throw InputError(source, problems);
    return params;
}

std::string save_tree_params(const TreeParams& params) {
    Writer w;
    visit_tree_params(params, w);
    return "// Tree preset saved by pleinair; every key resolved. Reference: README.md.\n" +
           w.root.dump(2) + "\n";
}

std::string tree_key_catalog(const TreeParams& params) {
    Cataloguer c;
    visit_tree_params(params, c);
    return c.rows.dump();
}

std::string tree_params_reference() {
    Documenter d;
    d.out << "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
    TreeParams defaults;
    visit_tree_params(defaults, d);
    return d.out.str();
}

}  // namespace pleinair
