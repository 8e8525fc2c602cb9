// Bonded spheres in motion: conservation laws, a cantilever against
// Euler-Bernoulli, hysteretic damping per cycle, and where the time step fails.

#include "SerialBondedSystem.H"
#include "TimeStep.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace iceDEM;
using iceDEM::test::SerialBondedSystem;

namespace
{

constexpr double density = 917.0;
constexpr double youngs = 5.4e8;

BondFamilyParameters unbreakableIce()
{
    BondFamilyParameters f;
    f.youngsModulus = youngs;
    f.poissonsRatio = 0.3;
    f.unbreakable = true;
    return f;
}

DampingParameters damping(DampingModel model, double alpha = 0.0)
{
    DampingParameters d;
    d.model = model;
    d.alpha = alpha;
    return d;
}

// A small jittered face-centred-cubic block of touching-or-nearly-touching spheres.
void fillBlock(SerialBondedSystem& system, int nx, int ny, int nz, double radius, unsigned seed)
{
    std::mt19937_64 rng(seed);
    const double spacing = 2.0 * radius * std::sqrt(2.0);   // fcc cube edge
    auto jitter = [&]() { return 0.02 * radius * (double(rng() % 2001) / 1000.0 - 1.0); };
    const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < nz; ++k)
                for (const Vec3& b : basis)
                {
                    const Vec3 x = spacing * (Vec3(i, j, k) + b) + Vec3(jitter(), jitter(), jitter());
                    system.addParticle(x, radius * 0.99, density);
                }
}

void randomVelocities(SerialBondedSystem& system, double speed, double spin, unsigned seed)
{
    std::mt19937_64 rng(seed);
    auto u = [&]() { return double(rng() % 20001) / 10000.0 - 1.0; };
    for (ParticleState& p : system.particles)
    {
        p.velocity = speed * Vec3(u(), u(), u());
        p.angularVelocity = spin * Vec3(u(), u(), u());
    }
}

double stepFor(double radius, double factor)
{
    return factor * 2.0 * radius * std::sqrt(density / youngs);
}

} // namespace


TEST(BondDynamics, LinearAndAngularMomentumConservedToRoundOff)
{
    SerialBondedSystem system(unbreakableIce(), damping(DampingModel::none));
    const double r = 0.02;
    fillBlock(system, 2, 2, 2, r, 7);
    system.bondWithin(1.1);
    ASSERT_GT(system.bonds.size(), 50u);
    randomVelocities(system, 0.05, 5.0, 11);

    const double dt = stepFor(r, 0.1);
    const Vec3 p0 = system.linearMomentum();
    const Vec3 l0 = system.angularMomentum();
    const double pScale = 0.05 * system.particles[0].mass * system.particles.size();
    const double lScale = pScale * 0.2;
    system.computeForces(dt);
    for (int s = 0; s < 2000; ++s)
    {
        system.step(dt);
    }
    EXPECT_LT((system.linearMomentum() - p0).norm() / pScale, 1e-12);
    EXPECT_LT((system.angularMomentum() - l0).norm() / lScale, 1e-12);
}

TEST(BondDynamics, EnergyDriftBelow1e4Over10000UndampedSteps)
{
    SerialBondedSystem system(unbreakableIce(), damping(DampingModel::none));
    const double r = 0.02;
    fillBlock(system, 2, 2, 2, r, 3);
    system.bondWithin(1.1);
    randomVelocities(system, 0.02, 2.0, 5);

    // Velocity Verlet's energy oscillates by O((omega dt)^2) about a constant
    // (its shadow energy); drift is the change of that mean, so compare
    // averages over the first and the last 1,000 steps.
    const double dt = stepFor(r, 0.1);
    system.computeForces(dt);
    const int steps = 10000, window = 1000;
    double first = 0.0, last = 0.0, worst = 0.0;
    const double e0 = system.kineticEnergy() + system.potentialEnergy();
    for (int s = 0; s < steps; ++s)
    {
        system.step(dt);
        const double e = system.kineticEnergy() + system.potentialEnergy();
        if (s < window) first += e / window;
        if (s >= steps - window) last += e / window;
        worst = std::max(worst, std::abs(e - e0) / e0);
    }
    // The run must actually exchange energy between springs and motion.
    EXPECT_GT(system.potentialEnergy(), 0.05 * e0);
    std::cout << "[ info ] energy drift " << std::abs(last - first) / first
              << ", largest excursion " << worst << std::endl;
    EXPECT_LT(std::abs(last - first) / first, 1e-4);
    EXPECT_LT(worst, 0.05) << "bounded oscillation";
}

TEST(BondDynamics, CantileverTipDeflectionMatchesEulerBernoulli)
{
    // A straight chain of bonded spheres, clamped at one end, loaded at the tip.
    DampingParameters d = damping(DampingModel::hysteretic, 0.7);
    SerialBondedSystem system(unbreakableIce(), d);
    const double r = 0.01;
    const int n = 21;
    for (int i = 0; i < n; ++i)
    {
        system.addParticle(Vec3(2.0 * r * i, 0.0, 0.0), r, density);
    }
    system.fixed[0] = true;
    for (int i = 0; i + 1 < n; ++i)
    {
        system.bond(i, i + 1);
    }
    const BondStiffness k = BondStiffness::of(system.model.parameters(), r, r);
    const double span = 2.0 * r * (n - 1);
    const double load = 1e-3 * 3.0 * k.youngsModulus * k.inertia / (span * span);   // tip deflection 1e-3 of span
    system.externalForce[n - 1] = Vec3(0.0, -load, 0.0);

    const double dt = stepFor(r, 0.2);
    system.computeForces(dt);
    const double expected = load * std::pow(span, 3) / (3.0 * k.youngsModulus * k.inertia);
    double previous = 0.0;
    for (int s = 0; s < 400000; ++s)
    {
        system.step(dt);
        if (s % 5000 == 0)
        {
            const double deflection = -system.particles[n - 1].position.y();
            if (s > 0 && std::abs(deflection - previous) < 1e-6 * expected)
            {
                break;
            }
            previous = deflection;
        }
    }
    const double deflection = -system.particles[n - 1].position.y();
    // The chain's shear springs add a Timoshenko term of 3 E I / (G A L^2), 0.1 % here.
    EXPECT_NEAR(deflection / expected, 1.0, 0.05);
    EXPECT_NEAR(deflection / expected, 1.0, 0.01) << "closer than the 5 % acceptance";
}

TEST(BondDynamics, HystereticDampingRemovesExpectedEnergyFractionPerCycle)
{
    // One sphere on one normal spring against a fixed sphere: with local
    // damping alpha, each half cycle scales the amplitude squared by
    // (1 - alpha)/(1 + alpha), so a cycle removes 1 - ((1-alpha)/(1+alpha))^2.
    for (double alpha : {0.05, 0.1, 0.3})
    {
        SerialBondedSystem system(unbreakableIce(), damping(DampingModel::hysteretic, alpha));
        const double r = 0.02;
        system.addParticle(Vec3::Zero(), r, density);
        system.addParticle(Vec3(2.0 * r, 0.0, 0.0), r, density);
        system.fixed[0] = true;
        system.bond(0, 1);
        const double amplitude = 1e-6;
        system.particles[1].position.x() += amplitude;

        const double dt = stepFor(r, 0.005);
        system.computeForces(dt);
        std::vector<double> peaks;
        double before = amplitude, now = amplitude;
        for (int s = 0; s < 200000 && peaks.size() < 3; ++s)
        {
            system.step(dt);
            const double next = system.particles[1].position.x() - 2.0 * r;
            if (now > before && now >= next && now > 0.0)
            {
                peaks.push_back(now);
            }
            before = now;
            now = next;
        }
        ASSERT_EQ(peaks.size(), 3u);
        const double perCycle = std::pow((1.0 - alpha) / (1.0 + alpha), 2);
        const double removed = 1.0 - std::pow(peaks[2] / peaks[1], 2);
        EXPECT_NEAR(removed, 1.0 - perCycle, 0.01 * (1.0 - perCycle)) << "alpha " << alpha;
        // Frequency independence: the same fraction from the first to the second peak.
        EXPECT_NEAR(std::pow(peaks[1] / peaks[0], 2), perCycle, 0.01 * perCycle);
    }
}

// The smallest time-step factor c (in steps of 5 %) at which the small pack's energy grows tenfold
// within 3,000 steps, with the given damping; 0 if none up to 3.
double firstUnstableFactor(const DampingParameters& dampingModel, double r)
{
    auto blowsUp = [&](double factor)
    {
        SerialBondedSystem system(unbreakableIce(), dampingModel);
        fillBlock(system, 2, 2, 2, r, 17);
        system.bondWithin(1.1);
        randomVelocities(system, 1e-3, 0.1, 23);
        const double dt = stepFor(r * 0.99, factor);
        system.computeForces(dt);
        const double e0 = system.kineticEnergy() + system.potentialEnergy();
        for (int s = 0; s < 3000; ++s)
        {
            system.step(dt);
            const double e = system.kineticEnergy() + system.potentialEnergy();
            if (!std::isfinite(e) || e > 10.0 * e0)
            {
                return true;
            }
        }
        return false;
    };
    for (double c = 0.05; c < 3.0; c *= 1.05)
    {
        if (blowsUp(c))
        {
            return c;
        }
    }
    return 0.0;
}

// The program's largest accepted factor for the small pack.
double programLimitFactor(double r)
{
    SerialBondedSystem probe(unbreakableIce(), damping(DampingModel::none));
    fillBlock(probe, 2, 2, 2, r, 17);
    probe.bondWithin(1.1);
    std::vector<int> count(probe.particles.size(), 0);
    for (const auto& b : probe.bonds)
    {
        ++count[b.a];
        ++count[b.b];
    }
    IceProperties props;
    props.families[0] = props.families[1] = unbreakableIce();
    props.material.youngsModulus = youngs;
    const TimeStepLimits limits =
        timeStepLimits(props, r * 0.99, *std::max_element(count.begin(), count.end()));
    return limits.limit / stepFor(r * 0.99, 1.0);
}

TEST(BondDynamics, ProgramLimitSitsBelowMeasuredInstabilityOfUndampedPack)
{
    const double r = 0.02;
    const double unstable = firstUnstableFactor(damping(DampingModel::none), r);
    ASSERT_GT(unstable, 0.0) << "the pack never went unstable";
    const double limitFactor = programLimitFactor(r);
    IceProperties props;
    std::cout << "[ info ] undamped pack unstable at c = " << unstable
              << "; program limit c = " << limitFactor
              << "; default c = " << props.timeStep.factor << std::endl;
    EXPECT_LT(limitFactor, unstable);
    EXPECT_GT(limitFactor, 0.2 * unstable) << "limit so low it wastes steps";
    EXPECT_LT(props.timeStep.factor, limitFactor);
}

// Issue 20's stability map, the small pack's row: damping (the cases' hysteretic alpha 0.1, viscous
// ratio 0.05) may move where the step fails; the program's limit must stay below it for each.
TEST(BondDynamics, ProgramLimitSitsBelowMeasuredInstabilityOfDampedPacks)
{
    const double r = 0.02;
    const double limitFactor = programLimitFactor(r);
    DampingParameters viscous = damping(DampingModel::viscous);
    viscous.dampingRatio = 0.05;
    for (const auto& [name, model] : {std::pair<const char*, DampingParameters>{"hysteretic 0.1",
                                          damping(DampingModel::hysteretic, 0.1)},
                                      {"viscous 0.05", viscous}})
    {
        const double unstable = firstUnstableFactor(model, r);
        ASSERT_GT(unstable, 0.0) << name << ": the pack never went unstable";
        std::cout << "[ info ] pack with " << name << " damping unstable at c = " << unstable
                  << "; program limit c = " << limitFactor << std::endl;
        EXPECT_LT(limitFactor, unstable) << name;
    }
}
