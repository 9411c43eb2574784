// Family seeds and parallel generation.
#include "pipeline/shot/family.h"

#include <tbb/parallel_for.h>

namespace pleinair {

uint64_t member_seed(uint64_t base_seed, uint32_t index) {
    return hash_keys(base_seed, static_cast<uint64_t>(Purpose::kFamily), index) & 0xffffffffull;
}

std::vector<Tree> generate_family(const TreeParams& params, uint64_t base_seed, uint32_t count,
                                  const TreeOptions& options) {
    std::vector<Tree> trees(count);
    tbb::parallel_for(uint32_t(0), count, [&](uint32_t i) {
        TreeOptions o = options;
        o.tree_id = i;
        trees[i] = generate_tree(params, member_seed(base_seed, i), o);
    });
    return trees;
}

}  // namespace pleinair
