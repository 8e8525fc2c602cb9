#include "divided.H"
#include "addToRunTimeSelectionTable.H"
#include "DynamicList.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(divided, 0);
addToRunTimeSelectionTable(fluidFractionModel, divided, dictionary);


divided::divided(const dictionary&)
{
    const scalar axis[4] = {-0.375, -0.125, 0.125, 0.375};
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
