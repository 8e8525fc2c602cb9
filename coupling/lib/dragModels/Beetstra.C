#include "Beetstra.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(Beetstra, 0);
addToRunTimeSelectionTable(dragModel, Beetstra, dictionary);


scalar Beetstra::F(scalar alpha, scalar Re)
{
    const scalar phi = 1.0 - alpha;
    const scalar a2 = sqr(alpha);
    scalar inertial = 0.0;
    if (Re > 0)
    {
        inertial = 0.413*Re/(24.0*a2)*(1.0/alpha + 3.0*phi*alpha + 8.4*pow(Re, -0.343))
                 / (1.0 + pow(10.0, 3.0*phi)*pow(Re, -0.5*(1.0 + 4.0*phi)));
    }
    return 10.0*phi/a2 + a2*(1.0 + 1.5*sqrt(phi)) + inertial;
}


scalar Beetstra::K(const dragInput& in) const
{
    const scalar Re = in.alpha*in.slipSpeed*in.diameter/in.nu;
    return stokes(in)*in.alpha*F(in.alpha, Re);
}

} // namespace iceCoupling
} // namespace Foam
