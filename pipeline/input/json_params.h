// Tree parameters as JSON text (comments allowed): parsing with one error line per problem and
// unknown keys rejected, saving every resolved key, and the reference table of every key.
#pragma once

#include <string>
#include <vector>

#include "generators/tree_params.h"

namespace pleinair {

// Starts from TreeParams' defaults and overrides the keys present. `overrides` are
// "POINTER=VALUE" strings (VALUE parsed as JSON, else taken as a string) applied before
// reading, so a tweaked value is validated like any other. Throws InputError listing every
// problem: syntax, unknown keys, wrong types, values out of range.
TreeParams parse_tree_params(const std::string& text, const std::string& source,
                             const std::vector<std::string>& overrides = {});

// Every key with its resolved value, in table order; parse_tree_params(save_tree_params(p))
// gives back p exactly.
std::string save_tree_params(const TreeParams& params);

// Markdown table of every key: pointer, default, range, unit and meaning.
std::string tree_params_reference();

// Every key as a JSON array of rows (pointer, kind, value from `params`, range, unit, doc) and
// of its objects (kind "group"), in table order: what a page of controls is built from.
std::string tree_key_catalog(const TreeParams& params);

}  // namespace pleinair
