#include "momentumCouplingModel.H"
#include "addToRunTimeSelectionTable.H"
#include "fvmSup.H"

namespace Foam
{
namespace iceCoupling
{

defineTypeNameAndDebug(momentumCouplingModel, 0);
defineRunTimeSelectionTable(momentumCouplingModel, dictionary);
defineTypeNameAndDebug(explicitCoupling, 0);
addToRunTimeSelectionTable(momentumCouplingModel, explicitCoupling, dictionary);
defineTypeNameAndDebug(semiImplicitCoupling, 0);
addToRunTimeSelectionTable(momentumCouplingModel, semiImplicitCoupling, dictionary);


autoPtr<momentumCouplingModel> momentumCouplingModel::New(const dictionary& couplingProperties)
{
    const word modelType
    (
        couplingProperties.getOrDefault<word>("momentumCoupling", semiImplicitCoupling::typeName)
    );
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);
    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            couplingProperties, "momentumCoupling", modelType, *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }
    return autoPtr<momentumCouplingModel>(cstrIter()(couplingProperties));
}


tmp<fvVectorMatrix> explicitCoupling::source
(
    const volScalarField&, const volVectorField&,
    const volVectorField& explicitForce, volVectorField& U
) const
{
    tmp<fvVectorMatrix> tm(new fvVectorMatrix(U, dimVelocity*dimVolume/dimTime));
    tm.ref() += explicitForce;
    return tm;
}


tmp<fvVectorMatrix> semiImplicitCoupling::source
(
    const volScalarField& Ksl, const volVectorField& KslUs,
    const volVectorField&, volVectorField& U
) const
{
    return KslUs - fvm::Sp(Ksl, U);
}

} // namespace iceCoupling
} // namespace Foam
