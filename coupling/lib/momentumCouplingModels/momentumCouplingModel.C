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


scalar momentumCouplingModel::stableCouplingTime(scalar a, scalar b) const
{
    // Both factors fall with dt from 1: bisect on the first dt where the
    // factor reaches -1 (the upper end doubles until it is unstable, or gives
    // up at 1e6 s where the scheme is unconditionally stable).
    scalar lo = 0, hi = 1/(a + b);
    while (mag(slipGrowthFactor(hi, a, b)) <= 1)
    {
        hi *= 2;
        if (hi > 1e6)
        {
            return GREAT;
        }
    }
    for (int i = 0; i < 60; ++i)
    {
        const scalar mid = 0.5*(lo + hi);
        (mag(slipGrowthFactor(mid, a, b)) <= 1 ? lo : hi) = mid;
    }
    return lo;
}


scalar explicitCoupling::slipGrowthFactor(scalar dt, scalar a, scalar b) const
{
    return 1 - dt*(a + b);
}


scalar semiImplicitCoupling::slipGrowthFactor(scalar dt, scalar a, scalar) const
{
    return 1 - dt*a;
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
