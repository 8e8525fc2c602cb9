#include "CompactionPlateLaw.H"

#include <gtest/gtest.h>

using namespace iceDEM;

namespace
{

const CompactionPlateLaw law{1.0e5, 20.0};
constexpr double r = 0.05;

} // namespace


TEST(CompactionPlateLaw, SphereBetweenThePlatesFeelsNothing)
{
    EXPECT_EQ(law.force(0.5, -0.3, r, 0.2, 0.8), 0.0);
    EXPECT_EQ(law.force(0.2 + r, 1.0, r, 0.2, 0.8), 0.0);   // just touching the floor plate
}


TEST(CompactionPlateLaw, SpringPushesOutOfEitherPlate)
{
    // 1 mm into the floor plate at rest: k * 1 mm up; into the lid: down
    EXPECT_NEAR(law.force(0.2 + r - 1e-3, 0.0, r, 0.2, 0.8), 100.0, 1e-9);
    EXPECT_NEAR(law.force(0.8 - r + 2e-3, 0.0, r, 0.2, 0.8), -200.0, 1e-9);
}


TEST(CompactionPlateLaw, DashpotActsOnTheVelocityRelativeToThePlate)
{
    // moving with the plate: the spring alone
    EXPECT_NEAR(law.force(0.2 + r - 1e-3, 0.05, r, 0.2, 0.8, 0.05, -0.05), 100.0, 1e-9);
    // moving into the floor plate at 1 m/s: + c * 1 m/s
    EXPECT_NEAR(law.force(0.2 + r - 1e-3, -1.0, r, 0.2, 0.8), 120.0, 1e-9);
    // into the lid moving down at 0.05 m/s while the sphere rises at 0.95 m/s: - c * 1 m/s
    EXPECT_NEAR(law.force(0.8 - r + 1e-3, 0.95, r, 0.2, 0.8, 0.0, -0.05), -120.0, 1e-9);
}


TEST(CompactionPlateLaw, APlateNeverPulls)
{
    // leaving the floor plate fast: the dashpot would pull, the total is zero
    EXPECT_EQ(law.force(0.2 + r - 1e-4, 10.0, r, 0.2, 0.8), 0.0);
    EXPECT_EQ(law.force(0.8 - r + 1e-4, -10.0, r, 0.2, 0.8), 0.0);
}


TEST(CompactionPlateLaw, SphereSqueezedByBothPlatesGetsTheirDifference)
{
    // a 0.1 m sphere between plates 0.098 m apart, 1 mm into each: the springs cancel
    EXPECT_NEAR(law.force(0.5, 0.0, r, 0.5 - 0.049, 0.5 + 0.049), 0.0, 1e-9);
}


TEST(CompactionPlateLaw, GapAndPorosityAreInverse)
{
    // 0.65 m3 of ice over 1 m2: porosity 0.35 needs a 1 m gap
    EXPECT_NEAR(gapForPorosity(0.65, 1.0, 0.35), 1.0, 1e-12);
    EXPECT_NEAR(porosityInGap(0.65, 1.0, 1.0), 0.35, 1e-12);
    EXPECT_NEAR(porosityInGap(0.4, 2.867, gapForPorosity(0.4, 2.867, 0.42)), 0.42, 1e-12);
}
