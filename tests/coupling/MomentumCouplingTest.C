// The growth factor of the slip velocity per coupling step of each momentum
// coupling scheme, and the longest stable coupling time, against their
// closed forms (drag alone, particle rate a = K/m_p, fluid rate b = Ksl/alpha).
#include "momentumCouplingModel.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace Foam;
using namespace Foam::iceCoupling;

namespace
{

autoPtr<momentumCouplingModel> scheme(const word& name)
{
    dictionary dict;
    dict.add("momentumCoupling", name);
    return momentumCouplingModel::New(dict);
}

} // namespace


TEST(MomentumCoupling, semiImplicitIsTheDefault)
{
    EXPECT_EQ(momentumCouplingModel::New(dictionary())->type(), "semiImplicit");
}


TEST(MomentumCoupling, explicitStableUpToTwoOverTheSumOfRates)
{
    auto ex = scheme("explicit");
    const scalar a = 45.2, b = 45.6;
    EXPECT_DOUBLE_EQ(ex->slipGrowthFactor(0.028, a, b), 1 - 0.028*(a + b));
    EXPECT_NEAR(ex->stableCouplingTime(a, b), 2/(a + b), 1e-12);
    EXPECT_FALSE(ex->implicitInFluid());
}


TEST(MomentumCoupling, semiImplicitStableUpToTwoOverTheRateDifference)
{
    auto si = scheme("semiImplicit");
    EXPECT_TRUE(si->implicitInFluid());
    // (1 - dt a)/(1 + dt b) = -1 at dt = 2/(a - b) when the particles relax faster (a > b) ...
    const scalar a = 80, b = 30;
    EXPECT_DOUBLE_EQ(si->slipGrowthFactor(0.01, a, b), (1 - 0.8)/(1 + 0.3));
    EXPECT_NEAR(si->stableCouplingTime(a, b), 2/(a - b), 1e-12);
    // ... and never when the fluid relaxes as fast (ice in a dense cloud: b ~ a).
    EXPECT_GT(si->stableCouplingTime(45.2, 45.6), 1e6);
    EXPECT_LT(std::abs(si->slipGrowthFactor(0.028, 45.2, 45.6)), 1);
}
