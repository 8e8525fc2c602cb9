#include "DiFelice.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(DiFelice, 0);
addToRunTimeSelectionTable(dragModel, DiFelice, dictionary);


scalar DiFelice::chi(scalar Re)
{
    // Below Re = 1e-10 the exponential term is zero to double precision.
    return 3.7 - 0.65*exp(-0.5*sqr(1.5 - log10(max(Re, 1e-10))));
}


scalar DiFelice::K(const dragInput& in) const
{
    const scalar Re = in.alpha*in.slipSpeed*in.diameter/in.nu;
    const scalar CdRe = sqr(0.63*sqrt(Re) + 4.8);
    // 0.5 rho C_d A alpha^(2-chi) |U_r| = 3 pi mu d (C_d Re / 24) alpha^(1-chi)
    return stokes(in)*CdRe/24.0*pow(in.alpha, 1.0 - chi(Re));
}

} // namespace iceCoupling
} // namespace Foam
