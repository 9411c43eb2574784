// Families: keyed member seeds and identical bytes on any number of threads.
#include "pipeline/shot/family.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <set>

#include "test_util.h"

namespace pleinair {
namespace {

TEST(Family, MemberSeedsAreDistinctAndIndependentOfFamilySize) {
    std::set<uint64_t> seeds;
    for (uint32_t i = 0; i < 1000; ++i) seeds.insert(member_seed(5, i));
    EXPECT_EQ(seeds.size(), 1000u);
    EXPECT_NE(member_seed(5, 0), member_seed(6, 0));
    TreeParams p = test::preset("shrub");
    auto three = generate_family(p, 5, 3), five = generate_family(p, 5, 5);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(test::hash_tree(three[i]), test::hash_tree(five[i]));
    EXPECT_EQ(five[4].id, 4u);
    EXPECT_EQ(five[4].leaves.tree_id.front(), 4u);
}

TEST(Family, OneAndTwoThreadsGiveTheSameBytes) {
    TreeParams p = test::preset("oak");
    std::vector<uint64_t> hashes[2];
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        for (const Tree& t : generate_family(p, 9, 6))
            hashes[threads - 1].push_back(test::hash_tree(t));
    }
    EXPECT_EQ(hashes[0], hashes[1]);
}

}  // namespace
}  // namespace pleinair
