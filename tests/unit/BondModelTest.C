// Two-particle tests of the four-spring bond against beam theory, and breakage
// exactly at each threshold and in each mode.

#include "BondModel.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace iceDEM;

namespace
{

constexpr double radius = 0.02;
constexpr double youngs = 5.4e8;
constexpr double poisson = 0.3;
constexpr double dt = 1e-6;

BondFamilyParameters iceFamily()
{
    BondFamilyParameters f;
    f.youngsModulus = youngs;
    f.poissonsRatio = poisson;
    f.strengthModel = StrengthModel::stress;
    f.tensileStrength = 1.0e6;
    f.shearStrength = 0.8e6;
    return f;
}

DampingParameters noDamping()
{
    DampingParameters d;
    d.model = DampingModel::none;
    return d;
}

struct Pair
{
    ParticleState a, b;
    Pair(double gap = 0.0)
    {
        a.radius = b.radius = radius;
        a.mass = b.mass = 917.0 * 4.0 / 3.0 * M_PI * std::pow(radius, 3);
        b.position = Vec3(2.0 * radius + gap, 0.0, 0.0);
    }
};

// Equivalent beam of length L = 2r, radius r, written out from beam theory.
const double beamLength = 2.0 * radius;
const double area = M_PI * radius * radius;
const double secondMoment = M_PI * std::pow(radius, 4) / 4.0;
const double polarMoment = M_PI * std::pow(radius, 4) / 2.0;
const double shearModulus = youngs / (2.0 * (1.0 + poisson));

} // namespace


TEST(BondStiffness, AxialSpringIsEAoverL)
{
    BondModel model(iceFamily(), noDamping());
    Pair p(0.001);
    BondState s = model.create(1, 2, p.a, p.b);
    const double stretch = 1e-7;
    p.b.position.x() += stretch;
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    const double expected = youngs * area / beamLength * stretch;
    EXPECT_NEAR(load.forceOnA.x() / expected, 1.0, 1e-6);
    EXPECT_NEAR(load.springNormalForce / expected, 1.0, 1e-6);
    EXPECT_NEAR(load.forceOnA.y(), 0.0, 1e-12 * expected);
}

TEST(BondStiffness, CompressionPushesApart)
{
    BondModel model(iceFamily(), noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    p.b.position.x() -= 1e-7;
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    EXPECT_LT(load.forceOnA.x(), 0.0);
}

// A compliant freeze-bond whose blocks bear on each other in compression: the
// normal spring is E A / L in tension and E_c A / L in compression, and its
// energy is that of the spring acting.
TEST(BondStiffness, CompressionModulusActsInCompressionOnly)
{
    BondFamilyParameters family = iceFamily();
    family.youngsModulus = 2.8e6;
    family.compressionModulus = youngs;
    BondModel model(family, noDamping());
    const double stretch = 1e-6;
    for (double sign : {1.0, -1.0})
    {
        Pair p;
        BondState s = model.create(1, 2, p.a, p.b);
        p.b.position.x() += sign * stretch;
        const BondLoad load = model.evaluate(s, p.a, p.b, dt);
        const double modulus = sign > 0.0 ? 2.8e6 : youngs;
        const double expected = sign * modulus * area / beamLength * stretch;
        EXPECT_NEAR(load.springNormalForce / expected, 1.0, 1e-6) << "sign " << sign;
        EXPECT_NEAR(load.forceOnA.x() / expected, 1.0, 1e-6) << "sign " << sign;
        const double energy = 0.5 * modulus * area / beamLength * stretch * stretch;
        EXPECT_NEAR(model.potentialEnergy(s, p.a, p.b) / energy, 1.0, 1e-6) << "sign " << sign;
    }
    // Without the entry the bond is as stiff in compression as in tension.
    EXPECT_DOUBLE_EQ(BondStiffness::of(iceFamily(), radius, radius).normalCompression,
                     BondStiffness::of(iceFamily(), radius, radius).normal);
}

TEST(BondStiffness, ShearSpringIsGAoverL)
{
    BondModel model(iceFamily(), noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    const double slip = 1e-8;
    p.b.velocity = Vec3(0.0, slip / dt, 0.0);
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    const double expected = shearModulus * area / beamLength * slip;
    // b is pushed back along -y; a is pulled along +y.
    EXPECT_NEAR(load.forceOnA.y() / expected, 1.0, 1e-6);
    // Lever-arm torques: the force on each particle acts at the contact point,
    // a distance r from its centre; both turn about +z here.
    EXPECT_NEAR(load.torqueOnA.z() / (radius * expected), 1.0, 1e-6);
    EXPECT_NEAR(load.torqueOnB.z() / (radius * expected), 1.0, 1e-6);
}

TEST(BondStiffness, TwistSpringIsGJoverL)
{
    BondModel model(iceFamily(), noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    const double angle = 1e-6;
    p.b.angularVelocity = Vec3(angle / dt, 0.0, 0.0);
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    const double expected = shearModulus * polarMoment / beamLength * angle;
    EXPECT_NEAR(load.torqueOnB.x() / -expected, 1.0, 1e-6);
    EXPECT_NEAR(load.torqueOnA.x() / expected, 1.0, 1e-6);
    EXPECT_NEAR(load.forceOnA.norm(), 0.0, 1e-12 * expected / radius);
}

TEST(BondStiffness, BendingSpringIsEIoverL)
{
    BondModel model(iceFamily(), noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    const double angle = 1e-6;
    // Equal and opposite spins: pure bending, no shear at the contact point.
    p.b.angularVelocity = Vec3(0.0, 0.0, 0.5 * angle / dt);
    p.a.angularVelocity = Vec3(0.0, 0.0, -0.5 * angle / dt);
    p.b.velocity = Vec3(0.0, -0.5 * angle / dt * radius, 0.0);
    p.a.velocity = Vec3(0.0, -0.5 * angle / dt * radius, 0.0);
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    const double expected = youngs * secondMoment / beamLength * angle;
    EXPECT_NEAR(load.torqueOnB.z() / -expected, 1.0, 1e-6);
    EXPECT_NEAR(load.torqueOnA.z() / expected, 1.0, 1e-6);
    EXPECT_NEAR(s.shearDisplacement.norm(), 0.0, 1e-18);
}

TEST(BondStiffness, RigidRotationLeavesSpringsUnloaded)
{
    BondModel model(iceFamily(), noDamping());
    Pair p(0.002);
    BondState s = model.create(1, 2, p.a, p.b);
    const Vec3 omega(0.3, -0.2, 0.7);
    const Vec3 centre = 0.5 * (p.a.position + p.b.position);
    for (ParticleState* q : {&p.a, &p.b})
    {
        q->angularVelocity = omega;
        q->velocity = omega.cross(q->position - centre);
    }
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    EXPECT_LT(s.shearDisplacement.norm(), 1e-18);
    EXPECT_LT(s.bendingAngle.norm(), 1e-18);
    EXPECT_LT(std::abs(s.twistAngle), 1e-18);
    EXPECT_LT(load.forceOnA.norm(), 1e-9);
}

TEST(BondStiffness, StoredVectorsFollowTheBondAndKeepTheirLength)
{
    // Stored shear and bending vectors normal to the bond along x; b then
    // stands at (1, 10, 0) from a, at rest: one step turns them into the new
    // tangent plane with their lengths.
    BondModel model(iceFamily(), noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    s.shearDisplacement = Vec3(0.0, 3e-6, 0.0);
    s.bendingAngle = Vec3(0.0, 0.0, 2e-4);
    const Vec3 n = Vec3(0.1, 1.0, 0.0).normalized();
    p.b.position = p.a.position + 2.0 * radius * n;
    model.evaluate(s, p.a, p.b, dt);
    EXPECT_NEAR(s.shearDisplacement.dot(n), 0.0, 1e-14 * 3e-6);
    EXPECT_NEAR(s.shearDisplacement.norm() / 3e-6, 1.0, 1e-14);
    EXPECT_NEAR(s.bendingAngle.dot(n), 0.0, 1e-14 * 2e-4);
    EXPECT_NEAR(s.bendingAngle.norm() / 2e-4, 1.0, 1e-14);
}

TEST(BondStiffness, UnequalRadiiUseSmallerRadiusAndSumLength)
{
    BondFamilyParameters f = iceFamily();
    f.radiusMultiplier = 0.8;
    const BondStiffness k = BondStiffness::of(f, 0.01, 0.03);
    const double rb = 0.008;
    EXPECT_NEAR(k.normal / (youngs * M_PI * rb * rb / 0.04), 1.0, 1e-12);
    EXPECT_NEAR(k.bending / (youngs * M_PI * std::pow(rb, 4) / 4.0 / 0.04), 1.0, 1e-12);
}


// ---------------------------------------------------------------------------
// Breakage: just below each limit the bond holds, just above it breaks in that mode.

namespace
{

struct ThresholdCase
{
    BreakageCriterion criterion;
    BreakMode mode;
};

class BondBreakage : public ::testing::TestWithParam<ThresholdCase> {};

// Loads one spring to `fraction` of its limit and evaluates once.
BondLoad loadTo(BreakMode mode, BreakageCriterion criterion, double fraction, StrengthModel strength)
{
    BondFamilyParameters f = iceFamily();
    f.criterion = criterion;
    f.strengthModel = strength;
    f.breakN = 0.0037;
    f.beta = 1.25;
    f.twistStrengthFactor = 0.7;
    f.bendingStrengthFactor = 1.3;
    BondModel model(f, noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    const BondStiffness k = BondStiffness::of(f, radius, radius);
    const double sigma = s.tensileStrength;
    const double tau = s.shearStrength;
    const double a15 = std::pow(k.area, 1.5);
    const bool combined = criterion == BreakageCriterion::combined;

    switch (mode)
    {
        case BreakMode::tension:
        {
            const double limit = sigma * k.area;
            p.b.position.x() += fraction * limit / k.normal;
            break;
        }
        case BreakMode::shear:
        {
            const double limit = tau * k.area;
            // Pure translation of b: lever arms make the contact point slip by v dt.
            p.b.velocity.y() = fraction * limit / k.shear / dt;
            break;
        }
        case BreakMode::twist:
        {
            const double limit = combined ? tau * k.polarInertia / k.bondRadius : f.twistStrengthFactor * tau * a15;
            p.b.angularVelocity.x() = fraction * limit / k.twist / dt;
            break;
        }
        case BreakMode::bending:
        {
            const double limit = combined ? sigma * k.inertia / k.bondRadius : f.bendingStrengthFactor * sigma * a15;
            const double angle = fraction * limit / k.bending;
            p.b.angularVelocity.z() = 0.5 * angle / dt;
            p.a.angularVelocity.z() = -0.5 * angle / dt;
            p.a.velocity.y() = p.b.velocity.y() = -0.5 * angle / dt * radius;
            break;
        }
        default:
            break;
    }
    return model.evaluate(s, p.a, p.b, dt);
}

} // namespace

TEST_P(BondBreakage, HoldsJustBelowAndBreaksJustAboveInTheRightMode)
{
    const ThresholdCase c = GetParam();
    for (StrengthModel strength : {StrengthModel::stress, StrengthModel::strain})
    {
        EXPECT_EQ(loadTo(c.mode, c.criterion, 1.0 - 1e-9, strength).broke, BreakMode::none)
            << toString(c.mode) << " " << toString(strength);
        EXPECT_EQ(loadTo(c.mode, c.criterion, 1.0 + 1e-9, strength).broke, c.mode)
            << toString(c.mode) << " " << toString(strength);
    }
}

INSTANTIATE_TEST_SUITE_P
(
    EachModeAndCriterion,
    BondBreakage,
    ::testing::Values
    (
        ThresholdCase{BreakageCriterion::separate, BreakMode::tension},
        ThresholdCase{BreakageCriterion::separate, BreakMode::shear},
        ThresholdCase{BreakageCriterion::separate, BreakMode::twist},
        ThresholdCase{BreakageCriterion::separate, BreakMode::bending},
        ThresholdCase{BreakageCriterion::combined, BreakMode::tension},
        ThresholdCase{BreakageCriterion::combined, BreakMode::shear},
        ThresholdCase{BreakageCriterion::combined, BreakMode::twist},
        ThresholdCase{BreakageCriterion::combined, BreakMode::bending}
    )
);

TEST(BondBreakageStrength, StrainModelGivesSigmaFromBreakNAndTauFromBeta)
{
    BondFamilyParameters f = iceFamily();
    f.strengthModel = StrengthModel::strain;
    f.breakN = 0.0037;
    f.beta = 1.25;
    BondModel model(f, noDamping());
    Pair p;
    const BondState s = model.create(1, 2, p.a, p.b);
    EXPECT_DOUBLE_EQ(s.tensileStrength, 0.0037 * youngs);
    EXPECT_DOUBLE_EQ(s.shearStrength, 1.25 * 0.0037 * youngs);
}

TEST(BondBreakageStrength, CombinedCriterionAddsBendingToTension)
{
    // Half the tensile limit plus half the bending limit reaches sigma_t together.
    BondFamilyParameters f = iceFamily();
    f.criterion = BreakageCriterion::combined;
    BondModel model(f, noDamping());
    const BondStiffness k = BondStiffness::of(f, radius, radius);
    for (double fraction : {0.5 - 1e-9, 0.5 + 1e-9})
    {
        Pair p;
        BondState s = model.create(1, 2, p.a, p.b);
        p.b.position.x() += fraction * f.tensileStrength * k.area / k.normal;
        const double angle = fraction * f.tensileStrength * k.inertia / k.bondRadius / k.bending;
        p.b.angularVelocity.z() = 0.5 * angle / dt;
        p.a.angularVelocity.z() = -0.5 * angle / dt;
        p.a.velocity.y() = p.b.velocity.y() = -0.5 * angle / dt * radius;
        const BreakMode mode = model.evaluate(s, p.a, p.b, dt).broke;
        EXPECT_EQ(mode == BreakMode::none, fraction < 0.5) << fraction;
    }
}

TEST(BondBreakageStrength, UnbreakableFamilyNeverBreaks)
{
    BondFamilyParameters f = iceFamily();
    f.unbreakable = true;
    BondModel model(f, noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    p.b.position.x() += 0.01;
    EXPECT_EQ(model.evaluate(s, p.a, p.b, dt).broke, BreakMode::none);
}

TEST(BondBreakageStrength, BrokenBondCarriesNoLoad)
{
    BondModel model(iceFamily(), noDamping());
    Pair p;
    BondState s = model.create(1, 2, p.a, p.b);
    p.b.position.x() += 0.01;
    const BondLoad load = model.evaluate(s, p.a, p.b, dt);
    EXPECT_EQ(load.broke, BreakMode::tension);
    EXPECT_EQ(load.forceOnA.norm(), 0.0);
    EXPECT_EQ(load.torqueOnA.norm() + load.torqueOnB.norm(), 0.0);
}
