#include "particleFluidCoupling.H"
#include "zeroGradientFvPatchFields.H"
#include "mathematicalConstants.H"

#include <mpi.h>

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
    stabilityCheck_(couplingProperties.getOrDefault<bool>("stabilityCheck", true)),
    drag_(dragModel::New(couplingProperties)),
    fraction_(fluidFractionModel::New(couplingProperties)),
    momentum_(momentumCouplingModel::New(couplingProperties)),
    locator_(mesh, fraction_(), couplingProperties),
    surface_(mesh, couplingProperties),
    smoothing_(mesh, couplingProperties),
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
    clampedCells_(0),
    lowestReported_(GREAT)
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


void particleFluidCoupling::setMixture
(
    const volScalarField& rho, const volScalarField& nu, scalar rhoWater, scalar g
)
{
    if (surface_.active())
    {
        FatalErrorInFunction
            << "a flat water surface (entry waterLevel) and a moving one (hydrodynamics vof)"
            << " exclude each other" << exit(FatalError);
    }
    mixtureRho_ = &rho;
    mixtureNu_ = &nu;
    rhoWater_ = rhoWater;
    gravity_ = g;
}


void particleFluidCoupling::setWaterHeight(const scalarField& columnHeight)
{
    columnHeight_ = &columnHeight;
}


void particleFluidCoupling::update
(
    const std::vector<::iceCoupling::CouplingParticle>& particles,
    const volVectorField& U,
    const volVectorField& gradp
)
{
    updateFluidFraction(particles);
    updateExchange(particles, U);
    updateForces(particles, U, gradp);
}


void particleFluidCoupling::updateFluidFraction
(
    const std::vector<::iceCoupling::CouplingParticle>& particles
)
{
    wetFraction_.setSize(particles.size());
    if (surface_.active())
    {
        std::vector<::iceCoupling::CouplingParticle> inWater(particles.size());
        forAll(wetFraction_, i)
        {
            wetFraction_[i] = surface_.submergedFraction(particles[i]);
            inWater[i] = surface_.inWater(particles[i]);
        }
        locator_.locate(inWater);
    }
    else
    {
        wetFraction_ = 1;
        locator_.locate(particles);
    }
    const scalarField& V = mesh_.V();
    scalarField solid(mesh_.nCells(), 0);
    vectorField solidMomentum(mesh_.nCells(), Zero);
    for (const particleSample& s : locator_.samples())
    {
        const auto& p = particles[s.particle];
        const scalar share = s.share*wetFraction_[s.particle]*volumeOf(p);
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
    scalarField solidFraction(solid/V);
    smoothing_.smooth(solidFraction);
    label clamped = 0;
    scalar lowest = 1;
    forAll(alpha, celli)
    {
        alpha[celli] = 1 - solidFraction[celli];
        lowest = min(lowest, alpha[celli]);
        if (alpha[celli] < alphaMin_)
        {
            alpha[celli] = alphaMin_;
            ++clamped;
        }
        Us[celli] = solid[celli] > 0 ? solidMomentum[celli]/solid[celli] : Zero;
    }
    clampedCells_ = returnReduce(clamped, sumOp<label>());
    lowest = returnReduce(lowest, minOp<scalar>());
    if (clampedCells_ > 0 && lowest < lowestReported_)
    {
        WarningInFunction
            << "fluid fraction below alphaMin = " << alphaMin_ << " (lowest " << lowest << ") in "
            << clampedCells_ << " cells at time " << mesh_.time().timeName()
            << "; clamped to alphaMin. Warned again only when it goes lower; every coupling step's "
            << "count is the clampedCells column of the particle output" << endl;
        lowestReported_ = lowest;
    }
    alpha_.correctBoundaryConditions();
    Us_.correctBoundaryConditions();
}


std::vector<double> particleFluidCoupling::atParticles
(
    label nParticles, const volVectorField& field, bool withAlpha
) const
{
    // Share-weighted over each particle's samples' cells, summed over the
    // ranks that hold them: (alpha,) then the field's three components.
    const int width = withAlpha ? 4 : 3;
    std::vector<double> values(width*nParticles, 0.0);
    for (const particleSample& s : locator_.samples())
    {
        double* row = &values[width*s.particle];
        if (withAlpha)
        {
            *row++ += s.share*alpha_[s.cell];
        }
        for (direction k = 0; k < 3; ++k)
        {
            row[k] += s.share*field[s.cell][k];
        }
    }
    locator_.exchange().sum(values, width);
    return values;
}


std::vector<double> particleFluidCoupling::scalarsAtParticles
(
    label nParticles, const UPtrList<const scalarField>& fields
) const
{
    const label width = fields.size();
    std::vector<double> values(width*nParticles, 0.0);
    for (const particleSample& s : locator_.samples())
    {
        double* row = &values[width*s.particle];
        for (label k = 0; k < width; ++k)
        {
            row[k] += s.share*fields[k][s.cell];
        }
    }
    locator_.exchange().sum(values, width);
    return values;
}


void particleFluidCoupling::updateExchange
(
    const std::vector<::iceCoupling::CouplingParticle>& particles,
    const volVectorField& U
)
{
    const label n = particles.size();
    const std::vector<double> atParticle(atParticles(n, U, true));
    K_.setSize(n);
    exchangeFluidVelocity_.setSize(n);
    std::vector<double> alphaAtParticle(n);
    rhoAtParticle_.setSize(n, rho_);
    std::vector<double> mixture;
    if (mixtureRho_)
    {
        UPtrList<const scalarField> fields(2);
        fields.set(0, &mixtureRho_->primitiveField());
        fields.set(1, &mixtureNu_->primitiveField());
        mixture = scalarsAtParticles(n, fields);
    }
    for (label i = 0; i < n; ++i)
    {
        const double* row = &atParticle[4*i];
        const auto& p = particles[i];
        alphaAtParticle[i] = row[0];
        exchangeFluidVelocity_[i] = vector(row[1], row[2], row[3]);
        const vector slip = exchangeFluidVelocity_[i] - toVector(p.velocity);
        const scalar nu = mixtureRho_ ? mixture[2*i + 1] : nu_;
        if (mixtureRho_)
        {
            rhoAtParticle_[i] = mixture[2*i];
        }
        K_[i] = wetFraction_[i]*drag_->K({p.diameter, row[0], mag(slip), rhoAtParticle_[i], nu});
    }
    checkStability(particles, alphaAtParticle);

    // The fluid's side: the same K, shared out as the particle's volume is,
    // and the reaction to the added mass of the last interval.
    const scalarField& V = mesh_.V();
    scalarField& Ksl = Ksl_.primitiveFieldRef();
    vectorField& KslUs = KslUs_.primitiveFieldRef();
    Ksl = 0;
    KslUs = Zero;
    const bool addedMassKnown = addedMassForce_.size() == n;
    for (const particleSample& s : locator_.samples())
    {
        const scalar rhoCell = mixtureRho_ ? (*mixtureRho_)[s.cell] : rho_;
        const scalar k = s.share*K_[s.particle]/(rhoCell*V[s.cell]);
        Ksl[s.cell] += k;
        KslUs[s.cell] += k*toVector(particles[s.particle].velocity);
        if (addedMassKnown)
        {
            KslUs[s.cell] -= s.share/(rhoCell*V[s.cell])*addedMassForce_[s.particle];
        }
    }
    Ksl_.correctBoundaryConditions();
    KslUs_.correctBoundaryConditions();
    explicitForce_.primitiveFieldRef() = KslUs - Ksl*U.primitiveField();
    explicitForce_.correctBoundaryConditions();
}


void particleFluidCoupling::updateForces
(
    const std::vector<::iceCoupling::CouplingParticle>& particles,
    const volVectorField& U,
    const volVectorField& gradp
)
{
    const label n = particles.size();
    if (K_.size() != n)
    {
        FatalErrorInFunction
            << "updateForces for " << n << " particles after updateExchange for " << K_.size()
            << abort(FatalError);
    }
    const std::vector<double> fluidVelocity(atParticles(n, U, false));
    const std::vector<double> pressureGradient(atParticles(n, gradp, false));
    std::vector<double> waterHeight;
    if (mixtureRho_)
    {
        if (!columnHeight_)
        {
            FatalErrorInFunction << "vof level: no water height set" << abort(FatalError);
        }
        UPtrList<const scalarField> fields(1);
        fields.set(0, columnHeight_);
        waterHeight = scalarsAtParticles(n, fields);
    }

    forces_.assign(n, {0.0, 0.0, 0.0});
    addedMassForce_.setSize(n);
    totalDrag_ = Zero;
    totalPressureForce_ = Zero;
    totalAddedMass_ = Zero;
    totalSubmergedVolume_ = 0;
    currentSlip_.clear();
    const labelList& centreCell = locator_.centreCells();
    for (label i = 0; i < n; ++i)
    {
        const auto& p = particles[i];
        // The fluid velocity the fluid's own share of the drag was solved
        // with: the new one where it is implicit, the frozen one where explicit.
        const vector Uf =
            momentum_->implicitInFluid()
          ? vector(fluidVelocity[3*i], fluidVelocity[3*i + 1], fluidVelocity[3*i + 2])
          : exchangeFluidVelocity_[i];
        const vector drag = K_[i]*(Uf - toVector(p.velocity));
        const vector gradient(pressureGradient[3*i], pressureGradient[3*i + 1], pressureGradient[3*i + 2]);
        vector pressure(Zero);
        scalar submerged = 0;
        if (mixtureRho_)
        {
            // The hydrostatic part exactly on the cap under the water height
            // of the particle's columns; the dynamic part on the same volume.
            const scalar r = 0.5*p.diameter;
            const scalar h = min(max(waterHeight[i] - (p.position[2] - r), scalar(0)), 2*r);
            submerged = constant::mathematical::pi*sqr(h)*(3*r - h)/3;
            pressure = submerged*(vector(0, 0, rhoWater_*gravity_) - gradient);
        }
        else
        {
            pressure = -rho_*wetFraction_[i]*volumeOf(p)*gradient;
        }
        addedMassForce_[i] = addedMass(p, Uf, i);
        // Every rank holding the particle has the same force; the rank with
        // its centre gives it.
        if (centreCell[i] < 0)
        {
            continue;
        }
        const vector total = drag + pressure + addedMassForce_[i];
        forces_[i] = {total.x(), total.y(), total.z()};
        totalDrag_ += drag;
        totalPressureForce_ += pressure;
        totalAddedMass_ += addedMassForce_[i];
        totalSubmergedVolume_ += submerged;
    }
    previousSlip_.swap(currentSlip_);

    if (Pstream::parRun())
    {
        std::vector<double> totals
        {
            totalDrag_.x(), totalDrag_.y(), totalDrag_.z(),
            totalPressureForce_.x(), totalPressureForce_.y(), totalPressureForce_.z(),
            totalAddedMass_.x(), totalAddedMass_.y(), totalAddedMass_.z(), totalSubmergedVolume_
        };
        MPI_Allreduce(MPI_IN_PLACE, totals.data(), int(totals.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        totalDrag_ = vector(totals[0], totals[1], totals[2]);
        totalPressureForce_ = vector(totals[3], totals[4], totals[5]);
        totalAddedMass_ = vector(totals[6], totals[7], totals[8]);
        totalSubmergedVolume_ = totals[9];
    }
}


::iceCoupling::CouplingRegion particleFluidCoupling::particleRegion() const
{
    const boundBox box(locator_.particleRegion(surface_.active() ? surface_.level() : GREAT));
    return {{box.min().x(), box.min().y(), box.min().z()}, {box.max().x(), box.max().y(), box.max().z()}};
}


tmp<fvVectorMatrix> particleFluidCoupling::momentumSource(volVectorField& U) const
{
    return momentum_->source(Ksl_, KslUs_, explicitForce_, U);
}


void particleFluidCoupling::checkStability
(
    const std::vector<::iceCoupling::CouplingParticle>& particles,
    const std::vector<double>& alphaAtParticle
) const
{
    if (!stabilityCheck_ || couplingTime_ <= 0)
    {
        return;
    }
    label worst = -1;
    scalar worstFactor = 1;
    scalar worstA = 0, worstB = 0;
    forAll(K_, i)
    {
        const auto& p = particles[i];
        if (p.mass <= 0)
        {
            continue;
        }
        const scalar alpha = alphaAtParticle[i];
        const scalar a = K_[i]/p.mass;
        if (K_[i] <= 0)
        {
            continue;   // out of the water
        }
        const scalar b = K_[i]*(1 - alpha)/(alpha*rhoAtParticle_[i]*wetFraction_[i]*volumeOf(p));
        const scalar factor = mag(momentum_->slipGrowthFactor(couplingTime_, a, b));
        if (factor > worstFactor)
        {
            worst = i;
            worstFactor = factor;
            worstA = a;
            worstB = b;
        }
    }
    if (worst >= 0)
    {
        FatalErrorInFunction
            << "the drag exchange is unstable with momentumCoupling "
            << momentum_->type() << " and a coupling time of " << couplingTime_ << " s: particle "
            << particles[worst].tag << " (fluid fraction " << alphaAtParticle[worst]
            << ", drag relaxation rate " << worstA << " 1/s, fluid's " << worstB
            << " 1/s) would see its slip velocity multiplied by " << worstFactor
            << " every coupling step. Stable up to a coupling time of "
            << momentum_->stableCouplingTime(worstA, worstB) << " s with " << momentum_->type()
            << (momentum_->type() == "explicit"
                ? word(" (semiImplicit allows more)") : word(""))
            << ": lower couplingInterval (constant/couplingProperties) and deltaT"
            << " (system/controlDict), or set stabilityCheck no to run it anyway"
            << exit(FatalError);
    }
}


vector particleFluidCoupling::addedMass
(
    const ::iceCoupling::CouplingParticle& p, const vector& fluidVelocity, label index
)
{
    const vector slip = fluidVelocity - toVector(p.velocity);
    if (addedMassCoefficient_ == 0)
    {
        return Zero;
    }
    currentSlip_[p.tag] = slip;
    const auto previous = previousSlip_.find(p.tag);
    if (previous == previousSlip_.end())
    {
        return Zero;
    }
    return addedMassCoefficient_*rhoAtParticle_[index]*wetFraction_[index]*volumeOf(p)
          *(slip - previous->second)/couplingTime_;
}


vector particleFluidCoupling::fluidExchangeTotal(const volVectorField& U) const
{
    const scalarField rhoV
    (
        mixtureRho_ ? scalarField(mixtureRho_->primitiveField()*mesh_.V()) : scalarField(rho_*mesh_.V())
    );
    if (momentum_->implicitInFluid())
    {
        return gSum(rhoV*(KslUs_.primitiveField() - Ksl_.primitiveField()*U.primitiveField()));
    }
    return gSum(rhoV*explicitForce_.primitiveField());
}

} // namespace iceCoupling
} // namespace Foam
