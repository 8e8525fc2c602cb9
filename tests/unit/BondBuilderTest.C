#include "BondBuilder.H"
#include "InputError.H"
#include "RandomPacking.H"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

using namespace iceDEM;

namespace
{

//- n^3 simple cubic lattice of touching spheres (radius 0.5, spacing 1), index x + n (y + n z).
std::vector<ParticleSpec> cubicLattice(int n)
{
    std::vector<ParticleSpec> particles;
    for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
    {
        ParticleSpec p;
        p.position = Vec3(x, y, z);
        p.radius = 0.5;
        particles.push_back(p);
    }
    return particles;
}

int latticeIndex(int n, int x, int y, int z)
{
    return x + n*(y + n*z);
}

IceProperties properties(double iceDistFactor, double freezeDistFactor, int maxBonds)
{
    IceProperties ice;
    ice.families[static_cast<int>(BondFamily::ice)].distFactor = iceDistFactor;
    ice.families[static_cast<int>(BondFamily::freeze)].distFactor = freezeDistFactor;
    ice.maxBondsPerParticle = maxBonds;
    return ice;
}

std::vector<int> bondsPerParticle(const std::vector<BondPair>& bonds, std::size_t n)
{
    std::vector<int> count(n, 0);
    for (const BondPair& b : bonds)
    {
        ++count[b.i];
        ++count[b.j];
    }
    return count;
}

void expectSortedAndOrdered(const std::vector<BondPair>& bonds)
{
    for (std::size_t k = 0; k < bonds.size(); ++k)
    {
        ASSERT_LT(bonds[k].i, bonds[k].j);
        if (k > 0)
        {
            ASSERT_TRUE(bonds[k - 1].i < bonds[k].i
                || (bonds[k - 1].i == bonds[k].i && bonds[k - 1].j < bonds[k].j));
        }
    }
}

} // namespace


TEST(BondBuilder, CubicLatticeDistFactor11GivesSixNeighbours)
{
    const int n = 5;
    const std::vector<ParticleSpec> particles = cubicLattice(n);
    BondBuilder builder(properties(1.1, 1.1, 16));
    const std::vector<BondPair> bonds = builder.build(particles);

    expectSortedAndOrdered(bonds);
    // Only the axial neighbours (d = 2r) lie within 1.1 * 2r; face diagonals (2.83 r) do not.
    EXPECT_EQ(bonds.size(), static_cast<std::size_t>(3*n*n*(n - 1)));
    const std::vector<int> count = bondsPerParticle(bonds, particles.size());
    for (int z = 1; z < n - 1; ++z)
    for (int y = 1; y < n - 1; ++y)
    for (int x = 1; x < n - 1; ++x)
    {
        EXPECT_EQ(count[latticeIndex(n, x, y, z)], 6);
    }
    EXPECT_EQ(count[latticeIndex(n, 0, 0, 0)], 3);
    EXPECT_EQ(count[latticeIndex(n, 2, 0, 0)], 4);
    EXPECT_EQ(count[latticeIndex(n, 2, 2, 0)], 5);
    for (const BondPair& b : bonds)
    {
        EXPECT_DOUBLE_EQ(b.distance, 1.0);
        EXPECT_EQ(b.family, BondFamily::ice);
    }

    const BondStatistics& s = builder.statistics();
    EXPECT_EQ(s.particleCount, n*n*n);
    EXPECT_EQ(s.totalBonds, static_cast<int>(bonds.size()));
    EXPECT_EQ(s.bondsPerFamily[0], s.totalBonds);
    EXPECT_EQ(s.bondsPerFamily[1], 0);
    EXPECT_EQ(s.minBondsPerParticle, 3);
    EXPECT_EQ(s.maxBondsPerParticle, 6);
    EXPECT_DOUBLE_EQ(s.meanBondsPerParticle, 2.0*s.totalBonds/(n*n*n));
    ASSERT_EQ(s.histogram.size(), 7u);
    EXPECT_EQ(s.histogram[3], 8);                   // corners
    EXPECT_EQ(s.histogram[4], 12*(n - 2));          // edges
    EXPECT_EQ(s.histogram[5], 6*(n - 2)*(n - 2));   // faces
    EXPECT_EQ(s.histogram[6], (n - 2)*(n - 2)*(n - 2));
    EXPECT_EQ(std::accumulate(s.histogram.begin(), s.histogram.end(), 0), n*n*n);
    const std::string summary = s.summary();
    EXPECT_NE(summary.find(std::to_string(s.totalBonds) + " bonds"), std::string::npos) << summary;
    EXPECT_NE(summary.find("ice"), std::string::npos) << summary;
    EXPECT_NE(summary.find("6:27"), std::string::npos) << summary;
}


TEST(BondBuilder, CubicLatticeDistFactor15AddsFaceDiagonals)
{
    // d = 2r (axial) and 2.83 r (face diagonal) lie within 1.5 * 2r = 3r; 3.46 r (body diagonal)
    // does not: 6 + 12 = 18 bonds inside.
    ASSERT_LT(std::sqrt(2.0), 1.5);
    ASSERT_GT(std::sqrt(3.0), 1.5);
    const int n = 5;
    const std::vector<ParticleSpec> particles = cubicLattice(n);
    BondBuilder builder(properties(1.5, 1.5, 18));
    const std::vector<BondPair> bonds = builder.build(particles);

    EXPECT_EQ(bonds.size(), static_cast<std::size_t>(3*n*n*(n - 1) + 6*n*(n - 1)*(n - 1)));
    const std::vector<int> count = bondsPerParticle(bonds, particles.size());
    for (int z = 1; z < n - 1; ++z)
    for (int y = 1; y < n - 1; ++y)
    for (int x = 1; x < n - 1; ++x)
    {
        EXPECT_EQ(count[latticeIndex(n, x, y, z)], 18);
    }
    for (const BondPair& b : bonds)
    {
        EXPECT_TRUE(std::abs(b.distance - 1.0) < 1e-15 || std::abs(b.distance - std::sqrt(2.0)) < 1e-15)
            << b.distance;
    }
    EXPECT_EQ(builder.statistics().maxBondsPerParticle, 18);
}


TEST(BondBuilder, CapacityExceededIsAnInputError)
{
    const std::vector<ParticleSpec> particles = cubicLattice(4);
    BondBuilder builder(properties(1.5, 1.5, 16));
    try
    {
        builder.build(particles);
        FAIL() << "18 bonds on a particle with maxBondsPerParticle 16 must be refused";
    }
    catch (const InputError& e)
    {
        const std::string what = e.what();
        EXPECT_EQ(e.file(), "constant/iceProperties");
        EXPECT_EQ(e.entry(), "maxBondsPerParticle");
        // The first interior particle is (1, 1, 1), index 21, at (1, 1, 1).
        EXPECT_NE(what.find("particle 21 at (1, 1, 1)"), std::string::npos) << what;
        EXPECT_NE(what.find("18 bonds"), std::string::npos) << what;
        EXPECT_NE(what.find("raise maxBondsPerParticle or lower distFactor"), std::string::npos) << what;
    }
}


TEST(BondBuilder, FamilyFollowsBlocks)
{
    // Blocks split the lattice at x = 2; the freeze family bonds touching spheres only.
    const int n = 4;
    std::vector<ParticleSpec> particles = cubicLattice(n);
    for (ParticleSpec& p : particles)
    {
        p.block = p.position.x() < 2.0 ? 3 : 5;
    }
    BondBuilder builder(properties(1.5, 1.0, 18));
    const std::vector<BondPair> bonds = builder.build(particles);

    int freeze = 0;
    for (const BondPair& b : bonds)
    {
        const bool sameBlock = particles[b.i].block == particles[b.j].block;
        EXPECT_EQ(b.family, sameBlock ? BondFamily::ice : BondFamily::freeze);
        if (!sameBlock)
        {
            EXPECT_DOUBLE_EQ(b.distance, 1.0);
            ++freeze;
        }
    }
    EXPECT_EQ(freeze, n*n);     // one axial bond across the x = 1.5 plane per (y, z)
    EXPECT_EQ(builder.statistics().bondsPerFamily[1], freeze);
    EXPECT_EQ(builder.statistics().bondsPerFamily[0], static_cast<int>(bonds.size()) - freeze);

    ParticleSpec a, b;
    a.radius = b.radius = 1.0;
    EXPECT_EQ(bondFamily(a, b), BondFamily::ice);       // both -1: no block, one solid
    b.block = 0;
    EXPECT_EQ(bondFamily(a, b), BondFamily::freeze);
    a.block = 0;
    EXPECT_EQ(bondFamily(a, b), BondFamily::ice);
}


TEST(BondBuilder, MatchesBruteForceOnARandomPacking)
{
    RandomPackingSpec spec;
    spec.hi = Vec3(0.4, 0.3, 0.3);
    spec.particleCount = 1500;
    spec.radiusSpread = 0.25;
    spec.seed = 3;
    std::vector<ParticleSpec> particles = buildRandomPacking(spec);
    for (ParticleSpec& p : particles)
    {
        p.block = p.position.x() < 0.2 ? -1 : (p.position.y() < 0.15 ? 0 : 1);
    }

    const IceProperties ice = properties(1.1, 1.3, 64);
    BondBuilder builder(ice);
    const std::vector<BondPair> bonds = builder.build(particles);

    std::vector<BondPair> expected;
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        for (std::size_t j = i + 1; j < particles.size(); ++j)
        {
            const BondFamily f = particles[i].block == particles[j].block
                ? BondFamily::ice : BondFamily::freeze;
            const double d = (particles[j].position - particles[i].position).norm();
            if (d <= ice.family(f).distFactor*(particles[i].radius + particles[j].radius))
            {
                expected.push_back({static_cast<int>(i), static_cast<int>(j), f, d});
            }
        }
    }
    ASSERT_EQ(bonds.size(), expected.size());
    for (std::size_t k = 0; k < bonds.size(); ++k)
    {
        EXPECT_EQ(bonds[k].i, expected[k].i);
        EXPECT_EQ(bonds[k].j, expected[k].j);
        EXPECT_EQ(bonds[k].family, expected[k].family);
        EXPECT_EQ(bonds[k].distance, expected[k].distance);
    }
    EXPECT_GT(builder.statistics().bondsPerFamily[1], 0);
    EXPECT_GT(builder.statistics().meanBondsPerParticle, 4.0);
}


TEST(BondBuilder, SkipFixedPairsLeavesOutPadBonds)
{
    const int n = 4;
    std::vector<ParticleSpec> particles = cubicLattice(n);
    for (ParticleSpec& p : particles)
    {
        p.fixed = p.position.x() < 1.5;   // the x = 0 and x = 1 layers
    }
    const IceProperties ice = properties(1.1, 1.1, 16);
    const std::vector<BondPair> all = BondBuilder(ice).build(particles);
    BondBuilder skipping(ice);
    skipping.skipFixedPairs();
    const std::vector<BondPair> kept = skipping.build(particles);

    // Fixed-fixed bonds: inside each of the two layers (2 * 2 n (n - 1)) and between them (n^2).
    EXPECT_EQ(all.size() - kept.size(), static_cast<std::size_t>(2*2*n*(n - 1) + n*n));
    for (const BondPair& b : kept)
    {
        EXPECT_FALSE(particles[b.i].fixed && particles[b.j].fixed);
    }
}


TEST(BondBuilder, EdgeCasesAndBadInput)
{
    BondBuilder builder(properties(1.1, 1.1, 16));
    EXPECT_TRUE(builder.build({}).empty());
    EXPECT_EQ(builder.statistics().totalBonds, 0);

    // Far-apart particles: no bonds, and no huge grid.
    std::vector<ParticleSpec> sparse = cubicLattice(2);
    sparse[7].position = Vec3(1e6, -1e6, 1e6);
    const std::vector<BondPair> bonds = builder.build(sparse);
    EXPECT_EQ(bonds.size(), 9u);
    EXPECT_EQ(builder.statistics().histogram[0], 1);

    std::vector<ParticleSpec> bad = cubicLattice(2);
    bad[3].radius = 0.0;
    EXPECT_THROW(builder.build(bad), std::invalid_argument);
    bad[3].radius = 0.5;
    bad[4].position.x() = std::nan("");
    EXPECT_THROW(builder.build(bad), std::invalid_argument);

    EXPECT_THROW(BondBuilder(properties(0.0, 1.1, 16)), InputError);
}
