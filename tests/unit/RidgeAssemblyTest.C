#include "RidgeAssembly.H"

#include "HydrostaticWater.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace iceDEM;

namespace
{

//- A keel of two blocks: a 6 x 4 x 5 cubic lattice of 0.1 m spheres, the
//  blocks split along x; the lattice top sits at z = 0.5.
std::vector<SavedParticle> latticeKeel()
{
    std::vector<SavedParticle> keel;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 5; ++k)
            {
                SavedParticle p;
                p.position = Vec3(0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.05 + 0.1 * k);
                p.radius = 0.05;
                p.block = i < 3 ? 0 : 1;
                keel.push_back(p);
            }
    return keel;
}

ConsolidatedLayerSpec layer(double thickness)
{
    ConsolidatedLayerSpec cl;
    cl.thickness = thickness;
    cl.length = 0.6;
    cl.width = 0.4;
    cl.particleDiameter = 0.05;
    return cl;
}

} // namespace


TEST(RidgeAssembly, TrimsTheKeelTopAndPlacesTheLayerOnWhatIsLeft)
{
    const std::vector<SavedParticle> keel = latticeKeel();
    const RidgeLayout r = assembleRidge(keel, layer(0.1), 0.08);
    // Top 0.5 m: centres above 0.42 go, i.e. the top layer of 24 spheres.
    EXPECT_NEAR(r.keelTop, 0.5, 1e-12);
    EXPECT_EQ(r.trimmedParticles, 24);
    EXPECT_EQ(r.keelParticles, 96);
    EXPECT_NEAR(r.clBottom, 0.4, 1e-12);
    EXPECT_NEAR(r.clTop, 0.5, 1e-12);
    EXPECT_EQ(r.clBlock, 2);
    int layerCount = 0;
    for (std::size_t k = 0; k < r.particles.size(); ++k)
    {
        const ParticleSpec& p = r.particles[k];
        if (k < static_cast<std::size_t>(r.keelParticles))
        {
            EXPECT_LE(p.position.z(), 0.42);
            EXPECT_EQ(p.block, keel[r.keelTagOfParticle[k] - 1].block);
            continue;
        }
        ++layerCount;
        EXPECT_EQ(p.block, r.clBlock);
        EXPECT_EQ(r.keelTagOfParticle[k], -1);
        EXPECT_GE(p.position.z() - p.radius, r.clBottom - 1e-9);     // on the keel, not in it
        EXPECT_LE(p.position.z() + p.radius, r.clTop + 1e-9);
    }
    // 0.6 x 0.4 x 0.1 m at solid fraction 0.6 of 50 mm spheres: 0.6 * 0.024 / 6.545e-5 = 220.
    EXPECT_EQ(layerCount, 220);
}


TEST(RidgeAssembly, NoLayerKeepsTheKeelWhole)
{
    const RidgeLayout r = assembleRidge(latticeKeel(), layer(0.0), 0.08);
    EXPECT_EQ(r.trimmedParticles, 0);
    EXPECT_EQ(r.keelParticles, 120);
    EXPECT_EQ(r.particles.size(), 120u);
    EXPECT_EQ(r.clBlock, -1);
}


TEST(RidgeAssembly, MeasuresLayersAndDepth)
{
    std::vector<SavedParticle> keel = latticeKeel();
    SavedParticle top;
    top.radius = 0.05;
    top.block = 7;
    for (int i = 0; i < 6; ++i)
    {
        top.position = Vec3(0.05 + 0.1 * i, 0.2, 0.55);
        keel.push_back(top);
    }
    const RidgeGeometry g = measureRidge(keel, 7, 0.6, 0.4);
    EXPECT_EQ(g.keelParticles, 120);
    EXPECT_EQ(g.layerParticles, 6);
    EXPECT_NEAR(g.keelBottom, 0.0, 1e-12);
    EXPECT_NEAR(g.keelTop, 0.5, 1e-12);
    EXPECT_NEAR(g.clBottom, 0.5, 1e-12);
    EXPECT_NEAR(g.clTop, 0.6, 1e-12);
    EXPECT_NEAR(g.depth(), 0.6, 1e-12);
    EXPECT_NEAR(g.particleRadius, 0.05, 1e-12);
    EXPECT_THROW(measureRidge({}, -1, 1, 1), std::invalid_argument);
}


TEST(RidgeAssembly, ALayerAloneIsPackedAsOnAKeel)
{
    // The CL packed as assembleRidge packs it on a keel (the same count; the
    // packing of a shifted box is another draw), from the given bottom: one
    // block, no keel; measureRidge puts the keel's bottom and top at the
    // layer's bottom, so that the depth is the layer's.
    const RidgeLayout onKeel = assembleRidge(latticeKeel(), layer(0.1), 0.08);
    const RidgeLayout alone = assembleLayerAlone(layer(0.1), 0.5);
    EXPECT_EQ(alone.keelParticles, 0);
    EXPECT_EQ(alone.clBlock, 0);
    EXPECT_NEAR(alone.clBottom, 0.5, 1e-12);
    EXPECT_NEAR(alone.clTop, 0.6, 1e-12);
    ASSERT_EQ(alone.particles.size(), onKeel.particles.size() - onKeel.keelParticles);
    std::vector<SavedParticle> saved;
    for (std::size_t k = 0; k < alone.particles.size(); ++k)
    {
        const ParticleSpec& p = alone.particles[k];
        EXPECT_GE(p.position.z() - p.radius, 0.5 - 1e-12);
        EXPECT_LE(p.position.z() + p.radius, 0.6 + 1e-12);
        EXPECT_EQ(p.block, 0);
        SavedParticle s;
        s.position = p.position;
        s.radius = p.radius;
        s.block = p.block;
        saved.push_back(s);
    }
    const RidgeGeometry g = measureRidge(saved, 0, 0.6, 0.4);
    EXPECT_EQ(g.keelParticles, 0);
    EXPECT_EQ(g.layerParticles, static_cast<int>(saved.size()));
    EXPECT_NEAR(g.keelBottom, g.clBottom, 1e-12);
    EXPECT_NEAR(g.keelTop, g.clBottom, 1e-12);
    EXPECT_NEAR(g.depth(), g.clTop - g.clBottom, 1e-12);
    EXPECT_THROW(assembleLayerAlone(layer(0.0), 0.5), std::invalid_argument);
}


TEST(RidgeAssembly, FloatingLevelBalancesWeightAndBuoyancy)
{
    std::vector<ParticleSpec> spheres;
    for (const SavedParticle& p : latticeKeel())
    {
        ParticleSpec s;
        s.position = p.position;
        s.radius = p.radius;
        spheres.push_back(s);
    }
    const double ratio = 917.0 / 1000.0;
    const double level = floatingWaterLevel(spheres, ratio);
    double submerged = 0.0, volume = 0.0;
    for (const ParticleSpec& s : spheres)
    {
        submerged += submergedSphereVolume(s.radius, level - (s.position.z() - s.radius));
        volume += 4.0 / 3.0 * M_PI * std::pow(s.radius, 3);
    }
    EXPECT_NEAR(submerged / volume, ratio, 1e-9);
    // Five layers of spheres: 4 fully under, the top one 58.5 % submerged by volume,
    // which puts the surface above the top layer's centre.
    EXPECT_GT(level, 0.45);
    EXPECT_LT(level, 0.5);
}


TEST(RidgeAssembly, RefusesBadInput)
{
    EXPECT_THROW(assembleRidge({}, layer(0.1), 0.05), std::invalid_argument);
    EXPECT_THROW(assembleRidge(latticeKeel(), layer(-0.1), 0.05), std::invalid_argument);
    EXPECT_THROW(assembleRidge(latticeKeel(), layer(0.1), -0.05), std::invalid_argument);
}


TEST(RidgeAssembly, OverlapStatisticsCountOnlyPairsOfDifferentBlocks)
{
    // Three spheres of radius 0.05 on a line: 0 and 1 (one block) overlap by
    // 3 mm, 1 and 2 (different blocks) by 1 mm, 2 and a fourth (different
    // blocks) stand 1 mm apart.
    std::vector<ParticleSpec> particles(4);
    const double x[] = {0.0, 0.097, 0.196, 0.297};
    const int block[] = {0, 0, 1, 2};
    std::vector<Vec3> positions;
    for (int k = 0; k < 4; ++k)
    {
        particles[k].radius = 0.05;
        particles[k].block = block[k];
        positions.emplace_back(x[k], 0.0, 0.0);
    }
    const OverlapStatistics stats = overlapStatistics(particles, positions);
    EXPECT_EQ(stats.touchingPairs, 1);
    EXPECT_NEAR(stats.meanOverlap, 0.001, 1e-12);
    EXPECT_NEAR(stats.maxOverlap, 0.001, 1e-12);

    positions[3].x() = 0.294;   // now it overlaps sphere 2 by 2 mm
    const OverlapStatistics two = overlapStatistics(particles, positions);
    EXPECT_EQ(two.touchingPairs, 2);
    EXPECT_NEAR(two.meanOverlap, 0.0015, 1e-12);
    EXPECT_NEAR(two.maxOverlap, 0.002, 1e-12);

    positions.pop_back();
    EXPECT_THROW(overlapStatistics(particles, positions), std::invalid_argument);
}
