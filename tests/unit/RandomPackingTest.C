#include "RandomPacking.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using namespace iceDEM;

namespace
{

constexpr double pi = 3.14159265358979323846;

//- A slice of the level-ice beam (2.9 x 0.5 x 0.55 m) at about the resolution of the 13,000
//  particle runs, small enough for a fast test.
RandomPackingSpec beamSlice(int count, double spread = 0.0)
{
    RandomPackingSpec spec;
    spec.lo = Vec3(0.0, 0.0, 0.0);
    spec.hi = Vec3(0.6, 0.5, 0.55);
    spec.particleCount = count;
    spec.radiusSpread = spread;
    spec.seed = 7;
    return spec;
}

double bruteForceMaxOverlap(const std::vector<ParticleSpec>& particles)
{
    double maxOverlap = 0.0;
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        for (std::size_t j = i + 1; j < particles.size(); ++j)
        {
            const double d = (particles[j].position - particles[i].position).norm();
            maxOverlap = std::max(maxOverlap, particles[i].radius + particles[j].radius - d);
        }
    }
    return maxOverlap;
}

double meanRadius(const std::vector<ParticleSpec>& particles)
{
    double sum = 0.0;
    for (const ParticleSpec& p : particles)
    {
        sum += p.radius;
    }
    return sum/particles.size();
}

double solidFraction(const std::vector<ParticleSpec>& particles, const RandomPackingSpec& spec)
{
    double volume = 0.0;
    for (const ParticleSpec& p : particles)
    {
        volume += 4.0/3.0*pi*std::pow(p.radius, 3);
    }
    return volume/(spec.hi - spec.lo).prod();
}

void expectInsideBox(const std::vector<ParticleSpec>& particles, const RandomPackingSpec& spec)
{
    const double eps = 1e-12;
    for (const ParticleSpec& p : particles)
    {
        for (int k = 0; k < 3; ++k)
        {
            ASSERT_GE(p.position[k] - p.radius, spec.lo[k] - eps);
            ASSERT_LE(p.position[k] + p.radius, spec.hi[k] + eps);
        }
    }
}

ParticleSpec at(double x, double y, double z)
{
    ParticleSpec p;
    p.position = Vec3(x, y, z);
    p.radius = 0.01;
    return p;
}

} // namespace


TEST(RandomPacking, MonodisperseIsDenseInsideTheBoxAndWithinTolerance)
{
    const RandomPackingSpec spec = beamSlice(2700);
    RandomPackingStats stats;
    const std::vector<ParticleSpec> particles = buildRandomPacking(spec, stats);

    ASSERT_EQ(particles.size(), 2700u);
    expectInsideBox(particles, spec);
    for (const ParticleSpec& p : particles)
    {
        EXPECT_EQ(p.radius, particles[0].radius);
        EXPECT_EQ(p.block, -1);
        EXPECT_EQ(p.material, 0);
        EXPECT_FALSE(p.fixed);
    }

    const double r = meanRadius(particles);
    const double overlap = bruteForceMaxOverlap(particles);
    EXPECT_LE(overlap, spec.overlapTolerance*r);
    EXPECT_NEAR(stats.maxOverlap, std::max(0.0, overlap)/r, 1e-9);
    EXPECT_NEAR(stats.solidFraction, solidFraction(particles, spec), 1e-9);
    EXPECT_NEAR(stats.meanRadius, r, 1e-15);
    EXPECT_EQ(stats.minRadius, stats.maxRadius);
    EXPECT_NEAR(stats.solidFraction, spec.targetSolidFraction*std::pow(stats.radiusScale, 3), 1e-9);
    // About 0.59 here; the beam at 13,000 particles reaches about 0.595.
    EXPECT_GE(stats.solidFraction, 0.57);
    EXPECT_LE(stats.solidFraction, spec.targetSolidFraction);
    EXPECT_GT(stats.iterations, 0);
    EXPECT_LE(stats.iterations, spec.maxIterations);
    RecordProperty("solidFraction", std::to_string(stats.solidFraction));
}


TEST(RandomPacking, PolydisperseRadiiStayWithinTheSpread)
{
    const RandomPackingSpec spec = beamSlice(2000, 0.3);
    RandomPackingStats stats;
    const std::vector<ParticleSpec> particles = buildRandomPacking(spec, stats);

    ASSERT_EQ(particles.size(), 2000u);
    expectInsideBox(particles, spec);
    const double centre = stats.nominalRadius*stats.radiusScale;
    double rMin = particles[0].radius, rMax = particles[0].radius;
    for (const ParticleSpec& p : particles)
    {
        EXPECT_GE(p.radius, centre*(1.0 - spec.radiusSpread)*(1.0 - 1e-12));
        EXPECT_LE(p.radius, centre*(1.0 + spec.radiusSpread)*(1.0 + 1e-12));
        rMin = std::min(rMin, p.radius);
        rMax = std::max(rMax, p.radius);
    }
    // The spread is really used: 2000 uniform draws come close to both ends.
    EXPECT_GT(rMax/rMin, (1.0 + 0.9*spec.radiusSpread)/(1.0 - 0.9*spec.radiusSpread));
    EXPECT_EQ(stats.minRadius, rMin);
    EXPECT_EQ(stats.maxRadius, rMax);
    EXPECT_LE(bruteForceMaxOverlap(particles), spec.overlapTolerance*meanRadius(particles));
    EXPECT_NEAR(stats.solidFraction, solidFraction(particles, spec), 1e-9);
    EXPECT_GE(stats.solidFraction, 0.57);
}


TEST(RandomPacking, DeterministicForASeedDifferentForAnother)
{
    RandomPackingSpec spec = beamSlice(800, 0.1);
    const std::vector<ParticleSpec> a = buildRandomPacking(spec);
    const std::vector<ParticleSpec> b = buildRandomPacking(spec);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        ASSERT_EQ(a[i].position, b[i].position);
        ASSERT_EQ(a[i].radius, b[i].radius);
    }

    spec.seed = 8;
    const std::vector<ParticleSpec> c = buildRandomPacking(spec);
    ASSERT_EQ(c.size(), a.size());
    int same = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        same += a[i].position == c[i].position;
    }
    EXPECT_EQ(same, 0);
}


TEST(RandomPacking, UnreachableTargetShrinksButMeetsTheTolerance)
{
    RandomPackingSpec spec = beamSlice(600);
    spec.targetSolidFraction = 0.72;
    spec.maxIterations = 300;
    RandomPackingStats stats;
    const std::vector<ParticleSpec> particles = buildRandomPacking(spec, stats);

    expectInsideBox(particles, spec);
    EXPECT_LT(stats.radiusScale, 1.0);
    EXPECT_LT(stats.solidFraction, 0.66);
    EXPECT_NEAR(stats.solidFraction, solidFraction(particles, spec), 1e-9);
    EXPECT_LE(bruteForceMaxOverlap(particles), spec.overlapTolerance*meanRadius(particles));
}


TEST(RandomPacking, SingleParticle)
{
    RandomPackingSpec spec;
    spec.hi = Vec3(1.0, 1.0, 1.0);
    spec.particleCount = 1;
    spec.targetSolidFraction = 0.1;
    RandomPackingStats stats;
    const std::vector<ParticleSpec> particles = buildRandomPacking(spec, stats);
    ASSERT_EQ(particles.size(), 1u);
    expectInsideBox(particles, spec);
    EXPECT_NEAR(stats.solidFraction, 0.1, 1e-12);
    EXPECT_TRUE(stats.converged);
}


TEST(RandomPacking, InvalidSpecsThrow)
{
    const RandomPackingSpec good = beamSlice(100);

    RandomPackingSpec s = good;
    s.particleCount = 0;
    EXPECT_THROW(buildRandomPacking(s), std::invalid_argument);

    s = good;
    s.hi.y() = s.lo.y();
    EXPECT_THROW(buildRandomPacking(s), std::invalid_argument);

    s = good;
    s.hi.z() = s.lo.z() - 1.0;
    EXPECT_THROW(buildRandomPacking(s), std::invalid_argument);

    for (double fraction : {0.0, -0.1, 0.74, 0.8})
    {
        s = good;
        s.targetSolidFraction = fraction;
        EXPECT_THROW(buildRandomPacking(s), std::invalid_argument) << fraction;
    }

    s = good;
    s.radiusSpread = 1.0;
    EXPECT_THROW(buildRandomPacking(s), std::invalid_argument);

    s = good;
    s.overlapTolerance = 0.0;
    EXPECT_THROW(buildRandomPacking(s), std::invalid_argument);

    // 100 particles at 0.6 in a 0.6 x 0.5 x 0.02 box need diameters of about 0.11.
    s = good;
    s.hi.z() = 0.02;
    try
    {
        buildRandomPacking(s);
        FAIL() << "a box thinner than a particle diameter must be refused";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("thinner than a particle diameter"), std::string::npos)
            << e.what();
    }
}


TEST(RandomPacking, MarkFixedEndsMarksBothPadsAlongTheAxis)
{
    const Vec3 lo(0.0, 0.0, 0.0), hi(2.9, 0.5, 0.55);
    std::vector<ParticleSpec> particles =
    {
        at(0.05, 0.2, 0.2), at(0.2, 0.2, 0.2), at(0.21, 0.2, 0.2), at(1.45, 0.1, 0.1),
        at(2.69, 0.2, 0.2), at(2.7, 0.2, 0.2), at(2.88, 0.2, 0.5)
    };
    markFixedEnds(particles, 0, 0.2, lo, hi);
    const std::vector<bool> expected = {true, true, false, false, false, true, true};
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        EXPECT_EQ(particles[i].fixed, expected[i]) << "particle " << i;
    }

    // Along z with a 0.1 pad: only the particles near z = 0 or z = 0.55 are added.
    std::vector<ParticleSpec> column = {at(1.0, 0.2, 0.05), at(1.0, 0.2, 0.3), at(1.0, 0.2, 0.5)};
    markFixedEnds(column, 2, 0.1, lo, hi);
    EXPECT_TRUE(column[0].fixed);
    EXPECT_FALSE(column[1].fixed);
    EXPECT_TRUE(column[2].fixed);

    EXPECT_THROW(markFixedEnds(column, 3, 0.1, lo, hi), std::invalid_argument);
    EXPECT_THROW(markFixedEnds(column, 0, -0.1, lo, hi), std::invalid_argument);
}


TEST(RandomPacking, FixedPadsOfABeamPacking)
{
    RandomPackingSpec spec;
    spec.hi = Vec3(2.9, 0.5, 0.55);
    spec.particleCount = 1200;
    std::vector<ParticleSpec> particles = buildRandomPacking(spec);
    markFixedEnds(particles, 0, 0.2, spec.lo, spec.hi);
    int fixed = 0;
    for (const ParticleSpec& p : particles)
    {
        const bool inPad = p.position.x() <= 0.2 || p.position.x() >= 2.7;
        EXPECT_EQ(p.fixed, inPad);
        fixed += p.fixed;
    }
    // About 0.4 / 2.9 of the particles, fewer near the walls.
    EXPECT_GT(fixed, 0.10*particles.size());
    EXPECT_LT(fixed, 0.16*particles.size());
}


TEST(RandomPacking, CountForDiameterFillsTheSheetToTheSolidFraction)
{
    // 0.94 x 1 x 0.1 m sheet of 50 mm spheres at 0.6: 0.6 * 0.094 / (pi 0.05^3 / 6) = 861.7
    const Vec3 lo = Vec3::Zero(), hi(0.94, 1.0, 0.1);
    EXPECT_EQ(particleCountForDiameter(lo, hi, 0.05, 0.0, 0.6), 862);
    // A spread of radii raises the mean volume by (1 + s^2): fewer particles.
    EXPECT_EQ(particleCountForDiameter(lo, hi, 0.05, 0.2, 0.6), static_cast<int>(std::lround(861.65 / 1.04)));
    EXPECT_THROW(particleCountForDiameter(lo, hi, 0.0, 0.0, 0.6), std::invalid_argument);
    EXPECT_THROW(particleCountForDiameter(lo, hi, 0.05, 1.0, 0.6), std::invalid_argument);
}
