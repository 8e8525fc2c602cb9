#include "SchillerNaumann.H"
#include "addToRunTimeSelectionTable.H"
#include "SchillerNaumannCorrelation.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(SchillerNaumann, 0);
addToRunTimeSelectionTable(dragModel, SchillerNaumann, dictionary);


scalar SchillerNaumann::CdRe(scalar Re)
{
    return iceDEM::schillerNaumannDragCoefficientTimesRe(Re);
}


scalar SchillerNaumann::K(const dragInput& in) const
{
    const scalar Re = in.slipSpeed*in.diameter/in.nu;
    // 0.5 rho C_d A |U_r| = 3 pi mu d (C_d Re / 24)
    return stokes(in)*CdRe(Re)/24.0;
}

} // namespace iceCoupling
} // namespace Foam
