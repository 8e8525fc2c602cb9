#include "fluidFractionModel.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(fluidFractionModel, 0);
defineRunTimeSelectionTable(fluidFractionModel, dictionary);


autoPtr<fluidFractionModel> fluidFractionModel::New(const dictionary& couplingProperties)
{
    const word modelType(couplingProperties.get<word>("fluidFractionModel"));
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);
    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            couplingProperties, "fluidFractionModel", modelType, *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }
    return autoPtr<fluidFractionModel>(cstrIter()(couplingProperties));
}

} // namespace iceCoupling
} // namespace Foam
