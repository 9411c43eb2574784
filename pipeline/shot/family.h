// Tree families: N members of one preset with seeds derived from one base seed, generated in
// parallel with identical results on any number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include "generators/tree.h"

namespace pleinair {

// Keyed on (base seed, index): member i's seed does not depend on the family's size. 32 bits so
// a seed reads and types easily.
uint64_t member_seed(uint64_t base_seed, uint32_t index);

// Member i has seed member_seed(base_seed, i) and tree id i. Parallel over members (TBB); each
// writes its own slot, so the thread count never changes a byte.
std::vector<Tree> generate_family(const TreeParams& params, uint64_t base_seed, uint32_t count,
                                  const TreeOptions& options = {});

}  // namespace pleinair
