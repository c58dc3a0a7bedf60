// The Verlet list (built through a cell grid) against brute force.
#include <algorithm>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/neighbor_list.hpp"

using namespace packbed;

namespace {

struct Cloud {
    std::vector<Vec3> centers;
    std::vector<double> radii;
};

/// Random spheres in a box, fixed seed; radii between 0.3 and 0.7 when `polydisperse`.
Cloud random_cloud(std::size_t n, double box, bool polydisperse, unsigned seed) {
    std::mt19937_64 rng(seed);
    auto u = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    Cloud c;
    for (std::size_t i = 0; i < n; ++i) {
        c.centers.push_back({box * u(), box * u(), 3.0 * box * u()});
        c.radii.push_back(polydisperse ? 0.3 + 0.4 * u() : 0.5);
    }
    return c;
}

std::set<std::pair<std::uint32_t, std::uint32_t>> pairs_of(const NeighborList& list,
                                                           std::size_t n) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::uint32_t i = 0; i < n; ++i)
        for (const auto j : list.neighbors_of(i)) {
            EXPECT_NE(i, j);
            pairs.emplace(std::min(i, j), std::max(i, j));
        }
    return pairs;
}

} // namespace

class NeighborListVsBruteForce : public ::testing::TestWithParam<std::tuple<double, bool>> {};

TEST_P(NeighborListVsBruteForce, SamePairs) {
    const auto [skin, polydisperse] = GetParam();
    const Cloud c = random_cloud(2000, 8.0, polydisperse, 42);
    NeighborList list;
    list.build(c.centers, c.radii, skin);
    const auto fast = pairs_of(list, c.centers.size());
    const auto slow = brute_force_pairs(c.centers, c.radii, skin);
    ASSERT_GT(slow.size(), 1000u); // the cloud is dense enough to test something
    EXPECT_EQ(fast, std::set(slow.begin(), slow.end()));
    // Full list: every pair appears in both rows, rows sorted.
    std::size_t entries = 0;
    for (std::size_t i = 0; i < c.centers.size(); ++i) {
        const auto row = list.neighbors_of(i);
        entries += row.size();
        EXPECT_TRUE(std::is_sorted(row.begin(), row.end()));
    }
    EXPECT_EQ(entries, 2 * slow.size());
}

INSTANTIATE_TEST_SUITE_P(Skins, NeighborListVsBruteForce,
                         ::testing::Combine(::testing::Values(0.0, 0.1, 0.4),
                                            ::testing::Values(false, true)));

TEST(NeighborList, SameRowsAndPairNumbersWhateverTheThreads) {
    // 2 000 spheres: above detail::parallel_min_spheres, so the rows are found by several
    // threads, each into its own buffer; the list must not depend on how they split the rows.
    const Cloud c = random_cloud(2000, 8.0, true, 5);
    auto rows_and_pairs = [&](int threads) {
        const int saved = omp_get_max_threads();
        omp_set_num_threads(threads);
        NeighborList list;
        list.build(c.centers, c.radii, 0.1);
        omp_set_num_threads(saved);
        std::vector<std::uint32_t> out;
        for (std::size_t i = 0; i < c.centers.size(); ++i) {
            const auto row = list.neighbors_of(i);
            const auto numbers = list.pair_numbers_of(i);
            out.push_back(static_cast<std::uint32_t>(row.size()));
            out.insert(out.end(), row.begin(), row.end());
            out.insert(out.end(), numbers.begin(), numbers.end());
        }
        return out;
    };
    const auto one = rows_and_pairs(1);
    ASSERT_GT(one.size(), 2 * 2000u + 2000u); // some rows have neighbours
    EXPECT_EQ(rows_and_pairs(2), one);
    EXPECT_EQ(rows_and_pairs(3), one);
}

TEST(NeighborList, RowsOnlyKeepTheRowsAndNoPairs) {
    const Cloud c = random_cloud(2000, 8.0, false, 9);
    NeighborList numbered, rows_only;
    numbered.build(c.centers, c.radii, 0.2);
    rows_only.build(c.centers, c.radii, 0.2, {}, false);
    ASSERT_GT(numbered.pairs(), 1000u);
    EXPECT_EQ(rows_only.pairs(), 0u);
    for (std::size_t i = 0; i < c.centers.size(); ++i) {
        const auto a = numbered.neighbors_of(i), b = rows_only.neighbors_of(i);
        ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "row " << i;
        EXPECT_TRUE(rows_only.upper_neighbors_of(i).empty());
        EXPECT_TRUE(rows_only.pair_numbers_of(i).empty());
    }
}

TEST(NeighborList, RebuildOnlyAfterHalfSkinDisplacement) {
    Cloud c = random_cloud(100, 4.0, false, 7);
    NeighborList list;
    EXPECT_TRUE(list.needs_rebuild(c.centers));
    list.build(c.centers, c.radii, 0.2);
    EXPECT_FALSE(list.needs_rebuild(c.centers));
    c.centers[17].x += 0.099; // below skin / 2
    EXPECT_FALSE(list.needs_rebuild(c.centers));
    c.centers[17].x += 0.002; // beyond skin / 2
    EXPECT_TRUE(list.needs_rebuild(c.centers));
}

TEST(NeighborList, ListStaysCompleteWhileNoSphereMovedHalfTheSkin) {
    // The Verlet guarantee: after moves below skin/2, every touching pair is still listed.
    Cloud c = random_cloud(1500, 7.0, false, 3);
    const double skin = 0.2;
    NeighborList list;
    list.build(c.centers, c.radii, skin);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> step(-0.057, 0.057); // |move| < 0.1 = skin/2
    for (auto& p : c.centers)
        p += Vec3{step(rng), step(rng), step(rng)};
    ASSERT_FALSE(list.needs_rebuild(c.centers));
    const auto listed = pairs_of(list, c.centers.size());
    for (const auto& pair : brute_force_pairs(c.centers, c.radii, 0.0))
        EXPECT_TRUE(listed.count(pair)) << pair.first << "-" << pair.second;
}

TEST(NeighborList, FarApartSpheresKeepTheGridSmall) {
    // Two spheres 1e9 apart: the grid must not try to allocate 1e9 cells.
    const std::vector<Vec3> centers{{0, 0, 0}, {0, 0, 1e9}, {0.5, 0, 0}};
    const std::vector<double> radii{0.5, 0.5, 0.5};
    NeighborList list;
    list.build(centers, radii, 0.1);
    EXPECT_EQ(list.neighbors_of(0).size(), 1u);
    EXPECT_EQ(list.neighbors_of(1).size(), 0u);
}

TEST(NeighborList, RowsFollowTheCallersKey) {
    // A reversed numbering as key: every row in decreasing index order, same pairs.
    const Cloud c = random_cloud(800, 6.0, false, 5);
    std::vector<std::uint32_t> key(c.centers.size());
    for (std::uint32_t i = 0; i < key.size(); ++i)
        key[i] = static_cast<std::uint32_t>(key.size()) - i;
    NeighborList plain, keyed;
    plain.build(c.centers, c.radii, 0.1);
    keyed.build(c.centers, c.radii, 0.1, key);
    for (std::size_t i = 0; i < c.centers.size(); ++i) {
        const auto a = plain.neighbors_of(i);
        const auto b = keyed.neighbors_of(i);
        ASSERT_EQ(a.size(), b.size());
        EXPECT_TRUE(std::equal(a.begin(), a.end(), b.rbegin())) << "sphere " << i;
    }
    EXPECT_DOUBLE_EQ(keyed.drift_limit2(), 0.05 * 0.05); // (skin / 2)^2
    EXPECT_EQ(keyed.reference()[9], c.centers[9]);
}

TEST(NeighborList, EveryPairIsNumberedOnceAndBothRowsFindIt) {
    const Cloud c = random_cloud(1500, 7.0, true, 8);
    std::vector<std::uint32_t> key(c.centers.size()); // rows in a shuffled order
    for (std::uint32_t i = 0; i < key.size(); ++i)
        key[i] = (i * 7919u) % static_cast<std::uint32_t>(key.size());
    NeighborList list;
    list.build(c.centers, c.radii, 0.1, key);
    const auto first = list.pair_first();
    const auto second = list.pair_second();
    ASSERT_EQ(first.size(), list.pairs());
    ASSERT_EQ(second.size(), list.pairs());
    EXPECT_EQ(2 * list.pairs(), [&] {
        std::size_t entries = 0;
        for (std::size_t i = 0; i < c.centers.size(); ++i)
            entries += list.neighbors_of(i).size();
        return entries;
    }());
    std::set<std::pair<std::uint32_t, std::uint32_t>> numbered;
    for (std::size_t p = 0; p < list.pairs(); ++p) {
        EXPECT_LT(first[p], second[p]);
        numbered.emplace(first[p], second[p]);
    }
    EXPECT_EQ(numbered, pairs_of(list, c.centers.size())); // each pair once
    for (std::uint32_t i = 0; i < c.centers.size(); ++i) {
        const auto row = list.neighbors_of(i);
        const auto numbers = list.pair_numbers_of(i);
        ASSERT_EQ(row.size(), numbers.size());
        for (std::size_t e = 0; e < row.size(); ++e) {
            const std::uint32_t p = numbers[e];
            ASSERT_LT(p, list.pairs());
            EXPECT_EQ(std::min(i, row[e]), first[p]);
            EXPECT_EQ(std::max(i, row[e]), second[p]);
        }
        // Upper neighbours: the row's j > i, in row order, numbered from first_pair_of(i).
        std::vector<std::uint32_t> upper;
        for (const std::uint32_t j : row)
            if (j > i)
                upper.push_back(j);
        const auto listed = list.upper_neighbors_of(i);
        EXPECT_TRUE(std::equal(upper.begin(), upper.end(), listed.begin(), listed.end()));
        for (std::size_t m = 0; m < listed.size(); ++m)
            EXPECT_EQ(first[list.first_pair_of(i) + m], i);
    }
}

TEST(SpatialOrder, IsAPermutationThatWalksTheCellsInOrder) {
    const Cloud c = random_cloud(3000, 10.0, false, 9);
    const double edge = 1.1;
    const auto order = spatial_order(c.centers, edge);
    ASSERT_EQ(order.size(), c.centers.size());
    std::vector<std::uint32_t> sorted(order);
    std::sort(sorted.begin(), sorted.end());
    for (std::uint32_t i = 0; i < sorted.size(); ++i)
        ASSERT_EQ(sorted[i], i);
    // Cell layers along z come one after another: the z cell index never decreases.
    double zmin = 1e300;
    for (const auto& p : c.centers)
        zmin = std::min(zmin, p.z);
    int last = 0;
    for (const auto i : order) {
        const int layer = static_cast<int>(std::floor((c.centers[i].z - zmin) / edge));
        EXPECT_GE(layer, last);
        last = layer;
    }
}

namespace {

/// All pairs (i < j) whose nearest copies in the periodic cell are closer than r_i + r_j +
/// margin, by brute force over the nine copies of j: the reference for the wrapped list.
std::set<std::pair<std::uint32_t, std::uint32_t>>
periodic_brute_force(const Cloud& c, const Periods& cell, double margin) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    const int z = cell.lz() > 0.0 ? 1 : 0;
    for (std::uint32_t i = 0; i < c.centers.size(); ++i)
        for (std::uint32_t j = i + 1; j < c.centers.size(); ++j) {
            const double cut = c.radii[i] + c.radii[j] + margin;
            for (int sx = -1; sx <= 1; ++sx)
                for (int sy = -1; sy <= 1; ++sy)
                    for (int sz = -z; sz <= z; ++sz) {
                        const Vec3 copy =
                            c.centers[j] + Vec3{sx * cell.lx(), sy * cell.ly(), sz * cell.lz()};
                        if (norm2(copy - c.centers[i]) < cut * cut)
                            pairs.emplace(i, j);
                    }
        }
    return pairs;
}

} // namespace

TEST(PeriodicNeighborList, SamePairsAsBruteForceOverTheCopies) {
    // Centres in the cell, a third of them within one diameter of a side; the search finds
    // the pairs that touch through a side and through a corner, each once.
    for (const double skin : {0.0, 0.1, 0.4}) {
        const Periodic cell(6.0, 5.0);
        Cloud c = random_cloud(900, 1.0, true, 21);
        for (auto& p : c.centers)
            p = {p.x * cell.lx(), p.y * cell.ly(), p.z * 5.0};
        NeighborList list;
        list.wrap(cell);
        list.build(c.centers, c.radii, skin);
        const auto slow = periodic_brute_force(c, cell, skin);
        std::size_t through_a_side = 0;
        for (const auto& [i, j] : slow)
            through_a_side +=
                norm(c.centers[j] - c.centers[i]) > c.radii[i] + c.radii[j] + skin ? 1 : 0;
        ASSERT_GT(through_a_side, 50u) << "skin " << skin; // the wrap is exercised
        EXPECT_EQ(pairs_of(list, c.centers.size()), slow) << "skin " << skin;
        std::size_t entries = 0;
        for (std::size_t i = 0; i < c.centers.size(); ++i) {
            const auto row = list.neighbors_of(i);
            entries += row.size();
            EXPECT_TRUE(std::adjacent_find(row.begin(), row.end()) == row.end()); // each once
        }
        EXPECT_EQ(entries, 2 * slow.size());
    }
}

TEST(PeriodicNeighborList, PeriodicAlongZTooSamePairsAsBruteForceOverThe27Copies) {
    // A cell periodic on all six faces (a random array's): pairs across the bottom and the
    // top, and across edges and corners of the cube, found once each, as by brute force; the
    // same cloud without the period along z loses the ones across z.
    const Periods cell(6.0, 5.0, 4.0);
    Cloud c = random_cloud(700, 1.0, true, 22);
    for (auto& p : c.centers)
        p = {p.x * cell.lx(), p.y * cell.ly(), p.z / 3.0 * cell.lz()}; // the cloud's z: [0, 3)
    NeighborList list;
    list.wrap(cell);
    list.build(c.centers, c.radii, 0.1);
    const auto slow = periodic_brute_force(c, cell, 0.1);
    EXPECT_EQ(pairs_of(list, c.centers.size()), slow);
    const auto flat = periodic_brute_force(c, Periods(6.0, 5.0), 0.1);
    ASSERT_GT(slow.size(), flat.size() + 30); // the pairs across z are exercised
    EXPECT_NEAR(cell.separation({1.0, 1.0, 0.2}, {1.0, 1.0, 3.9}).z, -0.3, 1e-15);
    EXPECT_DOUBLE_EQ(cell.wrapped({1.0, 1.0, -0.5}).z, 3.5);
    EXPECT_DOUBLE_EQ(Periods(6.0, 5.0).wrapped({1.0, 1.0, -0.5}).z, -0.5);
}

TEST(PeriodicNeighborList, CentresOutsideTheCellAreFoundByTheirCopies) {
    // A sphere at x = -0.2 (moved out since the last wrap) touches one at x = 3.6 in a cell of
    // 4: the separation is 0.2 through the side; and the narrowest cell allowed, two
    // diameters, lists a pair that is near both directly and through the side once.
    const Periodic cell(4.0, 4.0);
    const std::vector<Vec3> centers{{-0.2, 1.0, 1.0}, {3.6, 1.0, 1.0}, {1.5, 1.0, 1.0}};
    const std::vector<double> radii{0.5, 0.5, 0.5};
    NeighborList list;
    list.wrap(cell);
    list.build(centers, radii, 0.0);
    ASSERT_EQ(list.neighbors_of(0).size(), 1u);
    EXPECT_EQ(list.neighbors_of(0)[0], 1u);
    EXPECT_NEAR(norm(cell.separation(centers[0], centers[1])), 0.2, 1e-15);
    const Periodic narrow(2.0, 2.0);
    const std::vector<Vec3> two{{0.5, 1.0, 1.0}, {1.45, 1.0, 1.0}};
    NeighborList both;
    both.wrap(narrow);
    both.build(two, {radii.data(), 2}, 0.1); // 0.95 apart directly, 1.05 through the side
    ASSERT_EQ(both.neighbors_of(0).size(), 1u);
    EXPECT_EQ(both.pairs(), 1u);
    EXPECT_DOUBLE_EQ(narrow.separation(two[0], two[1]).x, 0.95);
    EXPECT_DOUBLE_EQ(narrow.separation(two[1], two[0]).x, -0.95);
}
