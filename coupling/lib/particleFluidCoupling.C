#include "particleFluidCoupling.H"
#include "parallelSum.H"
#include "zeroGradientFvPatchFields.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace iceCoupling
{

namespace
{

scalar volumeOf(const ::iceCoupling::CouplingParticle& p)
{
    return constant::mathematical::pi/6.0*pow3(p.diameter);
}

vector toVector(const std::array<double, 3>& a)
{
    return vector(a[0], a[1], a[2]);
}

IOobject fieldIO(const fvMesh& mesh, const word& name, bool written)
{
    return IOobject
    (
        name, mesh.time().timeName(), mesh, IOobject::NO_READ,
        written ? IOobject::AUTO_WRITE : IOobject::NO_WRITE
    );
}

} // namespace


particleFluidCoupling::particleFluidCoupling
(
    const fvMesh& mesh, const dictionary& couplingProperties, scalar rho, scalar nu,
    scalar couplingTime
)
:
    mesh_(mesh),
    rho_(rho),
    nu_(nu),
    alphaMin_(couplingProperties.getOrDefault<scalar>("alphaMin", 0.3)),
    addedMassCoefficient_(couplingProperties.getOrDefault<scalar>("addedMassCoefficient", 0)),
    couplingTime_(couplingTime),
    drag_(dragModel::New(couplingProperties)),
    fraction_(fluidFractionModel::New(couplingProperties)),
    momentum_(momentumCouplingModel::New(couplingProperties)),
    locator_(mesh, fraction_()),
    alpha_(fieldIO(mesh, "alpha", true), mesh, dimensionedScalar("one", dimless, 1.0),
           zeroGradientFvPatchScalarField::typeName),
    Us_(fieldIO(mesh, "Us", true), mesh, dimensionedVector("zero", dimVelocity, Zero),
        zeroGradientFvPatchVectorField::typeName),
    Ksl_(fieldIO(mesh, "Ksl", false), mesh, dimensionedScalar("zero", inv(dimTime), 0),
         zeroGradientFvPatchScalarField::typeName),
    KslUs_(fieldIO(mesh, "KslUs", false), mesh, dimensionedVector("zero", dimAcceleration, Zero),
           zeroGradientFvPatchVectorField::typeName),
    explicitForce_(fieldIO(mesh, "couplingForce", false), mesh,
                   dimensionedVector("zero", dimAcceleration, Zero),
                   zeroGradientFvPatchVectorField::typeName),
    totalDrag_(Zero),
    totalPressureForce_(Zero),
    totalAddedMass_(Zero),
    clampedCells_(0)
{
    if (addedMassCoefficient_ < 0)
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'addedMassCoefficient' is " << addedMassCoefficient_
            << ": it must be >= 0 (0.5 for a sphere, 0 for none)" << exit(FatalIOError);
    }
    if (addedMassCoefficient_ > 0 && couplingTime_ <= 0)
    {
        FatalErrorInFunction
            << "added mass needs the coupling time (got " << couplingTime_ << " s)"
            << exit(FatalError);
    }
    if (alphaMin_ <= 0 || alphaMin_ >= 1)
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'alphaMin' is " << alphaMin_
            << ": the lowest fluid fraction allowed must lie in (0, 1)" << exit(FatalIOError);
    }
    if (rho_ <= 0 || nu_ <= 0)
    {
        FatalErrorInFunction
            << "fluid density " << rho_ << " and viscosity " << nu_ << " must be positive"
            << exit(FatalError);
    }
}


void particleFluidCoupling::update
(
    const std::vector<::iceCoupling::CouplingParticle>& particles,
    const volVectorField& U,
    const volVectorField& gradp
)
{
    locator_.locate(particles);
    updateFluidFraction(particles);
    updateForces(particles, U, gradp);
}


void particleFluidCoupling::updateFluidFraction
(
    const std::vector<::iceCoupling::CouplingParticle>& particles
)
{
    const scalarField& V = mesh_.V();
    scalarField solid(mesh_.nCells(), 0);
    vectorField solidMomentum(mesh_.nCells(), Zero);
    for (const particleSample& s : locator_.samples())
    {
        const auto& p = particles[s.particle];
        const scalar share = s.share*volumeOf(p);
        if (fraction_->lumped() && share > (1 - alphaMin_)*V[s.cell])
        {
            FatalErrorInFunction
                << "particle " << p.tag << " (volume " << share << " m^3) sits in cell "
                << s.cell << " of volume " << V[s.cell] << " m^3: alone it fills more than"
                << " 1 - alphaMin = " << 1 - alphaMin_ << " of the cell, which fluidFractionModel"
                << " centre cannot represent. Use fluidFractionModel divided in"
                << " constant/couplingProperties, or cells larger than the particles"
                << exit(FatalError);
        }
        solid[s.cell] += share;
        solidMomentum[s.cell] += share*toVector(p.velocity);
    }

    scalarField& alpha = alpha_.primitiveFieldRef();
    vectorField& Us = Us_.primitiveFieldRef();
    label clamped = 0;
    scalar lowest = 1;
    forAll(alpha, celli)
    {
        alpha[celli] = 1 - solid[celli]/V[celli];
        lowest = min(lowest, alpha[celli]);
        if (alpha[celli] < alphaMin_)
        {
            alpha[celli] = alphaMin_;
            ++clamped;
        }
        Us[celli] = solid[celli] > 0 ? solidMomentum[celli]/solid[celli] : Zero;
    }
    clampedCells_ = returnReduce(clamped, sumOp<label>());
    if (clampedCells_ > 0)
    {
        WarningInFunction
            << "fluid fraction below alphaMin = " << alphaMin_ << " (lowest "
            << returnReduce(lowest, minOp<scalar>()) << ") in " << clampedCells_
            << " cells at time " << mesh_.time().timeName() << "; clamped to alphaMin" << endl;
    }
    alpha_.correctBoundaryConditions();
    Us_.correctBoundaryConditions();
}


void particleFluidCoupling::updateForces
(
    const std::vector<::iceCoupling::CouplingParticle>& particles,
    const volVectorField& U,
    const volVectorField& gradp
)
{
    // Fluid fraction, velocity and pressure gradient at each particle: its
    // samples' cells, share-weighted, summed over the ranks that hold them.
    constexpr int width = 7;
    const label n = particles.size();
    std::vector<double> atParticle(width*n, 0.0);
    for (const particleSample& s : locator_.samples())
    {
        double* row = &atParticle[width*s.particle];
        row[0] += s.share*alpha_[s.cell];
        for (direction k = 0; k < 3; ++k)
        {
            row[1 + k] += s.share*U[s.cell][k];
            row[4 + k] += s.share*gradp[s.cell][k];
        }
    }
    sumOverRanks(atParticle);

    forces_.assign(n, {0.0, 0.0, 0.0});
    scalarList K(n);
    vectorList addedMassForce(n, Zero);
    totalDrag_ = Zero;
    totalPressureForce_ = Zero;
    totalAddedMass_ = Zero;
    currentSlip_.resize(n);
    for (label i = 0; i < n; ++i)
    {
        const double* row = &atParticle[width*i];
        const auto& p = particles[i];
        const vector fluidVelocity(row[1], row[2], row[3]);
        const vector slip = fluidVelocity - toVector(p.velocity);
        K[i] = drag_->K({p.diameter, row[0], mag(slip), rho_, nu_});
        const vector drag = K[i]*slip;
        const vector pressure = -rho_*volumeOf(p)*vector(row[4], row[5], row[6]);
        addedMassForce[i] = addedMass(p, fluidVelocity, i);
        const vector total = drag + pressure + addedMassForce[i];
        forces_[i] = {total.x(), total.y(), total.z()};
        totalDrag_ += drag;
        totalPressureForce_ += pressure;
        totalAddedMass_ += addedMassForce[i];
    }
    previousSlip_.swap(currentSlip_);
    previousTags_.resize(n);
    for (label i = 0; i < n; ++i)
    {
        previousTags_[i] = particles[i].tag;
    }

    // The fluid's side: the same K, shared out as the particle's volume is.
    const scalarField& V = mesh_.V();
    scalarField& Ksl = Ksl_.primitiveFieldRef();
    vectorField& KslUs = KslUs_.primitiveFieldRef();
    Ksl = 0;
    KslUs = Zero;
    for (const particleSample& s : locator_.samples())
    {
        const scalar k = s.share*K[s.particle]/(rho_*V[s.cell]);
        Ksl[s.cell] += k;
        KslUs[s.cell] += k*toVector(particles[s.particle].velocity)
                       - s.share/(rho_*V[s.cell])*addedMassForce[s.particle];
    }
    Ksl_.correctBoundaryConditions();
    KslUs_.correctBoundaryConditions();
    explicitForce_.primitiveFieldRef() = KslUs - Ksl*U.primitiveField();
    explicitForce_.correctBoundaryConditions();
}


tmp<fvVectorMatrix> particleFluidCoupling::momentumSource(volVectorField& U) const
{
    return momentum_->source(Ksl_, KslUs_, explicitForce_, U);
}


vector particleFluidCoupling::addedMass
(
    const ::iceCoupling::CouplingParticle& p, const vector& fluidVelocity, label index
)
{
    currentSlip_[index] = fluidVelocity - toVector(p.velocity);
    const bool seenBefore =
        index < label(previousTags_.size()) && previousTags_[index] == p.tag;
    if (addedMassCoefficient_ == 0 || !seenBefore)
    {
        return Zero;
    }
    return addedMassCoefficient_*rho_*volumeOf(p)
          *(currentSlip_[index] - previousSlip_[index])/couplingTime_;
}


vector particleFluidCoupling::fluidExchangeTotal() const
{
    return rho_*gSum(mesh_.V()*explicitForce_.primitiveField());
}

} // namespace iceCoupling
} // namespace Foam
