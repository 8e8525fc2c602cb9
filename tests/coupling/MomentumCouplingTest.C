// The growth factor of the slip velocity per coupling step of each momentum
// coupling scheme in its least stable pattern, and the longest stable coupling
// time, against their closed forms (drag alone, particle rate a = K/m_p, fluid
// rate b = Ksl/alpha). Both limits were measured on tests/coupling/lightCloud:
// explicit stable at 22 ms and not at 24 ms for 2/(a + b) = 22.0 ms; semiImplicit
// stable at 40 ms and not at 100 ms for 2/a = 44 ms.
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


TEST(MomentumCoupling, semiImplicitStableUpToTwoOverTheParticleRate)
{
    auto si = scheme("semiImplicit");
    EXPECT_TRUE(si->implicitInFluid());
    // Whatever the fluid's rate: the particles relaxing alone bound it.
    for (const scalar b : {0.0, 30.0, 300.0})
    {
        EXPECT_DOUBLE_EQ(si->slipGrowthFactor(0.01, 80, b), 1 - 0.8);
        EXPECT_NEAR(si->stableCouplingTime(80, b), 2.0/80, 1e-12);
    }
    // The light cloud at 28 ms: explicit diverges, semi-implicit does not.
    EXPECT_LT(std::abs(si->slipGrowthFactor(0.028, 45.2, 45.6)), 1);
    EXPECT_GT(std::abs(scheme("explicit")->slipGrowthFactor(0.028, 45.2, 45.6)), 1);
}
