#include "divided.H"
#include "addToRunTimeSelectionTable.H"
#include "DynamicList.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(divided, 0);
addToRunTimeSelectionTable(fluidFractionModel, divided, dictionary);


divided::divided(const dictionary& couplingProperties)
{
    const label n = couplingProperties.getOrDefault<label>("dividedPointsPerDiameter", 4);
    if (n < 2 || n > 20)
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'dividedPointsPerDiameter' is " << n
            << ": the lattice of sample points needs 2 to 20 points across a diameter"
            << exit(FatalIOError);
    }
    scalarList axis(n);
    forAll(axis, i)
    {
        axis[i] = (i + 0.5)/n - 0.5;
    }
    DynamicList<vector> inside;
    for (const scalar x : axis)
    {
        for (const scalar y : axis)
        {
            for (const scalar z : axis)
            {
                const vector p(x, y, z);
                if (magSqr(p) <= 0.25)
                {
                    inside.append(p);
                }
            }
        }
    }
    offsets_.transfer(inside);
    shares_.setSize(offsets_.size(), 1.0/offsets_.size());
}

} // namespace iceCoupling
} // namespace Foam
