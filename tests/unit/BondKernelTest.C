// The bond kernels (generic and AVX2) on batches of different bonds against
// BondModel::evaluate, which runs the kernel on each bond alone: lanes do not
// mix, the loads land in their slots, the screen never hides a break, and both
// instruction sets agree, bit for bit.

#include "BondBatches.H"
#include "BondKernel.H"
#include "BondModel.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace iceDEM;

namespace
{

constexpr double dt = 1e-6;

BondFamilyParameters iceFamily()
{
    BondFamilyParameters f;
    f.youngsModulus = 5.4e8;
    f.poissonsRatio = 0.3;
    f.strengthModel = StrengthModel::stress;
    f.tensileStrength = 1.0e6;
    f.shearStrength = 0.8e6;
    return f;
}

bool sameBits(double x, double y)
{
    return std::memcmp(&x, &y, sizeof x) == 0;
}

//- Random bonds between pairs of random radii, stretched, compressed (so
//  that the contact spring is cancelled), sheared, spinning, some breaking,
//  one with no history at all; the last batch is incomplete.
struct RandomBonds
{
    static constexpr int count = 43;
    std::vector<ParticleState> particles;
    std::vector<BondState> states;

    explicit RandomBonds(const BondModel& model)
    {
        std::mt19937 random(7);
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        auto vector = [&](double scale) -> Vec3 { return Vec3(unit(random), unit(random), unit(random)) * scale; };
        for (int i = 0; i < count; ++i)
        {
            ParticleState a, b;
            a.radius = 0.02 * (1.0 + 0.3 * unit(random));
            b.radius = 0.02 * (1.0 + 0.3 * unit(random));
            a.mass = 917.0 * 4.0 / 3.0 * M_PI * std::pow(a.radius, 3);
            b.mass = 917.0 * 4.0 / 3.0 * M_PI * std::pow(b.radius, 3);
            a.position = vector(1.0);
            const Vec3 direction = vector(1.0).normalized();
            b.position = a.position + (a.radius + b.radius) * direction;
            BondState s = model.create(2 * i + 1, 2 * i + 2, a, b);
            if (i > 0)
            {
                s.shearDisplacement = vector(1e-6);
                s.bendingAngle = vector(1e-4);
                s.twistAngle = 1e-4 * unit(random);
            }
            const double stretch = i % 5 == 4 ? 1e-3 : 2e-6 * unit(random);
            b.position += stretch * direction + vector(1e-6);
            a.velocity = vector(0.01);
            b.velocity = vector(0.01);
            a.angularVelocity = vector(0.5);
            b.angularVelocity = vector(0.5);
            particles.push_back(a);
            particles.push_back(b);
            states.push_back(s);
        }
    }
};

void expectKernelMatchesModel(BondKernel kernel, const DampingParameters& damping)
{
    const BondModel model(iceFamily(), damping);
    const RandomBonds bonds(model);
    std::vector<KernelAtom> atoms;
    for (const ParticleState& p : bonds.particles)
    {
        atoms.push_back(kernelAtomOf(p));
    }
    std::vector<BondStiffness> stiffnesses;
    BondBatches batches;
    batches.resize(RandomBonds::count);
    for (int i = 0; i < RandomBonds::count; ++i)
    {
        const ParticleState& a = bonds.particles[2 * i];
        const ParticleState& b = bonds.particles[2 * i + 1];
        stiffnesses.push_back(BondStiffness::of(model.parameters(), a.radius, b.radius));
        batches.set(i, 2 * i, 2 * i + 1, bonds.states[i], stiffnesses.back(),
                    model.intactBounds(bonds.states[i], stiffnesses.back()));
        // Bond i's loads on a and b go to slots 2i and 2i + 1; the padding's to the last.
        batches.setLoadSlots(i, 2 * i, 2 * i + 1);
    }
    batches.pad();
    for (std::size_t i = RandomBonds::count; i < batches.batches() * bondKernelLanes; ++i)
    {
        batches.setLoadSlots(i, 2 * RandomBonds::count, 2 * RandomBonds::count);
    }
    BondKernelSettings settings;
    settings.dt = dt;
    settings.viscous = damping.model == DampingModel::viscous && damping.dampingRatio > 0.0;
    settings.dampingRatio = damping.dampingRatio;
    std::vector<BondEndLoad> loads(2 * RandomBonds::count + 1);

    int broken = 0, surelyIntact = 0;
    for (int first = 0; first < RandomBonds::count; first += bondKernelLanes)
    {
        BondKernelResult result;
        const int mayBreak = kernel(atoms.data(), batches.batch(first / bondKernelLanes), loads.data(), settings, result);
        for (int i = first; i < std::min(first + bondKernelLanes, RandomBonds::count); ++i)
        {
            const int l = i - first;
            const ParticleState& a = bonds.particles[2 * i];
            const ParticleState& b = bonds.particles[2 * i + 1];
            BondState alone = bonds.states[i];
            const BondLoad load = model.evaluate(alone, stiffnesses[i], a, b, dt);
            const BreakMode mode = model.breakMode
            (
                bonds.states[i], stiffnesses[i], result.springNormalForce[l],
                result.shearForce2[l], result.twistTorque2[l], result.bendingTorque2[l]
            );
            EXPECT_EQ(mode, load.broke) << i;
            if (!(mayBreak >> l & 1))
            {
                EXPECT_EQ(load.broke, BreakMode::none) << i;
                ++surelyIntact;
            }
            broken += mode != BreakMode::none;
            BondState stepped = bonds.states[i];
            batches.copyHistory(i, stepped);
            const Vec3 forceOnA = load.forceOnA;
            if (mode != BreakMode::none)
            {
                continue;   // evaluate gives no load; the caller drops the kernel's
            }
            EXPECT_TRUE(sameBits(stepped.twistAngle, alone.twistAngle)) << i;
            for (int c = 0; c < 3; ++c)
            {
                EXPECT_TRUE(sameBits(stepped.shearDisplacement[c], alone.shearDisplacement[c])) << i << c;
                EXPECT_TRUE(sameBits(stepped.bendingAngle[c], alone.bendingAngle[c])) << i << c;
                EXPECT_TRUE(sameBits(result.centre[c][l], load.centre[c])) << i << c;
                EXPECT_TRUE(sameBits(loads[2 * i].force[c], forceOnA[c])) << i << c;
                EXPECT_TRUE(sameBits(loads[2 * i + 1].force[c], -forceOnA[c])) << i << c;
                EXPECT_TRUE(sameBits(loads[2 * i].moment[c], load.torqueOnA[c])) << i << c;
                EXPECT_TRUE(sameBits(loads[2 * i + 1].moment[c], load.torqueOnB[c])) << i << c;
            }
        }
    }
    EXPECT_GT(broken, 0);
    EXPECT_GT(surelyIntact, 0);
    EXPECT_LT(broken, RandomBonds::count);
}

DampingParameters viscous()
{
    DampingParameters d;
    d.model = DampingModel::viscous;
    d.dampingRatio = 0.3;
    return d;
}

DampingParameters hysteretic()
{
    DampingParameters d;
    d.model = DampingModel::hysteretic;
    d.alpha = 0.1;
    return d;
}

} // namespace


TEST(BondBatch, GenericKernelHasTheSingleBondBits)
{
    expectKernelMatchesModel(bondKernelGeneric, viscous());
    expectKernelMatchesModel(bondKernelGeneric, hysteretic());
}

TEST(BondBatch, Avx2KernelHasTheSingleBondBits)
{
    if (!__builtin_cpu_supports("avx2"))
    {
        GTEST_SKIP() << "this processor has no AVX2";
    }
    expectKernelMatchesModel(bondKernelAvx2, viscous());
    expectKernelMatchesModel(bondKernelAvx2, hysteretic());
}
