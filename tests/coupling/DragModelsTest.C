// Each drag law against its published formula at points worked by hand, and
// the limits every law must reach (Stokes drag for a lone sphere at Re -> 0).
#include "SchillerNaumann.H"
#include "DiFelice.H"
#include "Beetstra.H"
#include "mathematicalConstants.H"

#include <gtest/gtest.h>

using namespace Foam;
using namespace Foam::iceCoupling;

namespace
{

const scalar pi = constant::mathematical::pi;
const scalar rho = 1000, nu = 1e-6, d = 2e-3;

//- The slip speed that gives this particle Reynolds number at fluid fraction alpha.
scalar slipFor(scalar Re, scalar alpha = 1) { return Re*nu/(alpha*d); }

scalar stokesK() { return 3*pi*rho*nu*d; }

scalar area() { return pi*d*d/4; }

autoPtr<dragModel> law(const word& name)
{
    dictionary dict;
    dict.add("dragModel", name);
    return dragModel::New(dict);
}

} // namespace


TEST(DragModels, schillerNaumannStokesLimit)
{
    EXPECT_NEAR(law("SchillerNaumann")->K({d, 1, slipFor(1e-9), rho, nu})/stokesK(), 1.0, 1e-6);
}


TEST(DragModels, schillerNaumannIntermediateAndNewtonRegime)
{
    auto sn = law("SchillerNaumann");
    // Re = 1: C_d = 24 (1 + 0.15) = 27.6
    const scalar u1 = slipFor(1);
    EXPECT_NEAR(sn->K({d, 1, u1, rho, nu}), 0.5*rho*27.6*area()*u1, 1e-12);
    // Re = 100: C_d = 0.24 (1 + 0.15 * 100^0.687) = 0.24 (1 + 0.15 * 23.659197) = 1.091731
    const scalar u100 = slipFor(100);
    EXPECT_NEAR(sn->K({d, 1, u100, rho, nu})/(0.5*rho*area()*u100), 1.091731, 1e-6);
    // Re = 2000: Newton regime, C_d = 0.44
    const scalar u2000 = slipFor(2000);
    EXPECT_NEAR(sn->K({d, 1, u2000, rho, nu})/(0.5*rho*area()*u2000), 0.44, 1e-12);
    // Fluid fraction plays no part in the single-particle law.
    EXPECT_DOUBLE_EQ(sn->K({d, 0.5, u100, rho, nu}), sn->K({d, 1, u100, rho, nu}));
}


TEST(DragModels, diFeliceLoneSphere)
{
    // alpha = 1, Re = 1: C_d = (0.63 + 4.8)^2 = 29.4849
    const scalar u = slipFor(1);
    EXPECT_NEAR(law("DiFelice")->K({d, 1, u, rho, nu})/(0.5*rho*area()*u), 29.4849, 1e-10);
}


TEST(DragModels, diFeliceVoidageExponent)
{
    // At Re = 10^1.5 the exponent is chi = 3.7 - 0.65 = 3.05, and the drag at
    // fluid fraction alpha is alpha^(2 - chi) times that at alpha = 1 for the
    // same superficial slip alpha |U_r| (same Re, same C_d): F ~ (alpha |U_r|)^2 alpha^-chi.
    const scalar Re = std::pow(10.0, 1.5);
    EXPECT_NEAR(DiFelice::chi(Re), 3.05, 1e-12);
    auto df = law("DiFelice");
    const scalar alpha = 0.6;
    const scalar F1 = df->K({d, 1, slipFor(Re), rho, nu})*slipFor(Re);
    const scalar Fa = df->K({d, alpha, slipFor(Re, alpha), rho, nu})*slipFor(Re, alpha);
    EXPECT_NEAR(Fa/F1, std::pow(alpha, -3.05), 1e-12);
    // Re -> 0: chi -> 3.7 and C_d Re -> 4.8^2 = 23.04
    EXPECT_NEAR(df->K({d, 1, slipFor(1e-12), rho, nu})/stokesK(), 23.04/24, 1e-5);
}


TEST(DragModels, beetstraLimits)
{
    auto bs = law("Beetstra");
    // A lone sphere at Re -> 0: Stokes drag.
    EXPECT_NEAR(bs->K({d, 1, slipFor(1e-10), rho, nu})/stokesK(), 1.0, 1e-6);
    // Dense and slow, alpha = 0.6: F = 10 * 0.4/0.36 + 0.36 (1 + 1.5 sqrt(0.4)), whose first
    // term is the Carman-Kozeny pressure drop (Ergun's viscous term with 180 for 150).
    const scalar F = 10*0.4/0.36 + 0.36*(1 + 1.5*std::sqrt(0.4));
    EXPECT_NEAR(Beetstra::F(0.6, 0), F, 1e-12);
    EXPECT_NEAR(bs->K({d, 0.6, 0, rho, nu}), stokesK()*0.6*F, 1e-12*stokesK());
}


TEST(DragModels, beetstraInertialTerm)
{
    // alpha = 0.6, Re = 100, worked by hand:
    // 0.413*100/(24*0.36) = 4.7800926; 1/0.6 + 3*0.4*0.6 + 8.4*100^-0.343 = 1.6666667 + 0.72 + 1.7309291
    // 10^1.2 * 100^-1.3 = 15.848932 * 0.0025118864 = 0.0398107
    const scalar inertial = 4.7800926*(1.6666667 + 0.72 + 1.7309291)/(1 + 0.0398107);
    const scalar F = 10*0.4/0.36 + 0.36*(1 + 1.5*std::sqrt(0.4)) + inertial;
    EXPECT_NEAR(Beetstra::F(0.6, 100)/F, 1.0, 1e-6);
}


TEST(DragModels, unknownNameRefusedWithTheChoices)
{
    const bool previous = FatalIOError.throwExceptions();
    dictionary dict;
    dict.add("dragModel", "Stokes");
    try
    {
        dragModel::New(dict);
        ADD_FAILURE() << "an unknown drag law was accepted";
    }
    catch (const Foam::IOerror& e)
    {
        const std::string msg = e.message();
        EXPECT_NE(msg.find("Stokes"), std::string::npos) << msg;
        EXPECT_NE(msg.find("SchillerNaumann"), std::string::npos) << msg;
        EXPECT_NE(msg.find("DiFelice"), std::string::npos) << msg;
        EXPECT_NE(msg.find("Beetstra"), std::string::npos) << msg;
    }
    FatalIOError.throwExceptions(previous);
}
