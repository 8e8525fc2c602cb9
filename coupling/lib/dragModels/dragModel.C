#include "dragModel.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(dragModel, 0);
defineRunTimeSelectionTable(dragModel, dictionary);


autoPtr<dragModel> dragModel::New(const dictionary& couplingProperties)
{
    const word modelType(couplingProperties.get<word>("dragModel"));
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);
    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            couplingProperties, "dragModel", modelType, *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }
    return autoPtr<dragModel>(cstrIter()(couplingProperties));
}


scalar dragModel::stokes(const dragInput& in)
{
    return 3.0*constant::mathematical::pi*in.rho*in.nu*in.diameter;
}

} // namespace iceCoupling
} // namespace Foam
