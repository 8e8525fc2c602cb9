#include "SchillerNaumann.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(SchillerNaumann, 0);
addToRunTimeSelectionTable(dragModel, SchillerNaumann, dictionary);


scalar SchillerNaumann::CdRe(scalar Re)
{
    return max(0.44*Re, 24.0*(1.0 + 0.15*pow(Re, 0.687)));
}


scalar SchillerNaumann::K(const dragInput& in) const
{
    const scalar Re = in.slipSpeed*in.diameter/in.nu;
    // 0.5 rho C_d A |U_r| = 3 pi mu d (C_d Re / 24)
    return stokes(in)*CdRe(Re)/24.0;
}

} // namespace iceCoupling
} // namespace Foam
