#include "centre.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(centre, 0);
addToRunTimeSelectionTable(fluidFractionModel, centre, dictionary);


centre::centre(const dictionary&)
:
    offsets_(1, Zero),
    shares_(1, 1.0)
{}

} // namespace iceCoupling
} // namespace Foam
