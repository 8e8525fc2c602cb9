#include "BondedBody.H"

#include "IceBondForces.H"
#include "InertiaScalingFix.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "PlatenLoading.H"
#include "TimeStep.H"

#include "atom.h"
#include "group.h"
#include "lammps.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

BondedBody buildBondedBody
(
    const RandomPackingSpec& spec,
    const IceProperties& ice,
    const std::string& icePropertiesPath,
    const std::function<void(std::vector<ParticleSpec>&)>& markFixed,
    const std::function<void(const std::string&)>& log,
    double inertiaScaling
)
{
    BondedBody body;
    body.inertiaScaling = inertiaScaling;
    body.particles = buildRandomPacking(spec, body.packing);
    if (markFixed)
    {
        markFixed(body.particles);
    }
    const RandomPackingStats& stats = body.packing;
    std::ostringstream msg;
    msg << "Packing: " << body.particles.size() << " particles, radius " << stats.minRadius << " - "
        << stats.maxRadius << " m, solid fraction " << stats.solidFraction << " (target "
        << spec.targetSolidFraction << "; the box walls leave voids a packing cannot fill), largest overlap "
        << stats.maxOverlap << " of the mean radius";
    log(msg.str());

    BondBuilder builder(ice);
    body.bondPairs = builder.build(body.particles);
    body.bondStats = builder.statistics();
    log("Bonds: " + body.bondStats.summary());

    const double minMass = ice.material.density * 4.0 / 3.0 * M_PI * std::pow(stats.minRadius, 3);
    body.contact = ContactParameters::of(ice, 2.0 * stats.meanRadius, minMass);

    const TimeStepLimits limits =
        timeStepLimits(ice, stats.minRadius, body.bondStats.maxBondsPerParticle, inertiaScaling);
    body.dt = chooseTimeStep(ice, limits, icePropertiesPath);
    std::ostringstream step;
    step << "Time step " << body.dt << " s (limit " << limits.limit << " s; stiffest spring: "
         << limits.stiffestSpringName << ", critical " << limits.stiffestSpring << " s";
    if (inertiaScaling != 1.0)
    {
        step << "; inertia scaled by " << inertiaScaling;
    }
    step << ")";
    if (body.dt > limits.limit)
    {
        step << " ABOVE THE LIMIT: timeStep.refuseUnsafe no";
    }
    log(step.str());
    return body;
}


AttachedForces::AttachedForces() = default;
AttachedForces::AttachedForces(AttachedForces&&) noexcept = default;
AttachedForces& AttachedForces::operator=(AttachedForces&&) noexcept = default;
AttachedForces::~AttachedForces() = default;


std::string AttachedForces::failure() const
{
    std::string f = bonds ? bonds->failure() : std::string();
    if (f.empty() && inertia)
    {
        f = inertia->failure();
    }
    return f;
}


AttachedForces attachIceBonds
(
    LiggghtsInstance& lmp,
    const IceProperties& ice,
    const BondedBody& body,
    PlatenLoading& loading,
    const Checkpoint* resume,
    const std::function<void()>& afterBondFix
)
{
    AttachedForces attached;
    attached.bonds = IceBondForces::define(lmp, ice);
    std::unique_ptr<IceBondForces>& bonds = attached.bonds;
    if (afterBondFix)
    {
        afterBondFix();
    }
    if (body.inertiaScaling != 1.0)
    {
        attached.inertia = std::make_unique<InertiaScalingFix>(lmp, body.inertiaScaling);
        attached.inertia->define();
    }
    // LIGGGHTS' set-up of the first run resets property/atom values to their
    // defaults, so the bonds are stored after it.
    lmp.command("run 0");
    if (resume)
    {
        loading.resumeFrom(*resume, lmp, *bonds);
    }
    else
    {
        bonds->createBonds(body.particles, body.bondPairs);
    }
    lmp.command("run 0");   // forces of the first step with the bonds in place
    return attached;
}


long stopParticlesOutside(LiggghtsInstance& lmp, const Vec3& lo, const Vec3& hi, int fixedType)
{
    LAMMPS_NS::LAMMPS& engine = lmp.engine();
    LAMMPS_NS::Atom& atom = *engine.atom;
    const int mobileBit = engine.group->bitmask[engine.group->find("mobile")];
    long stopped = 0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (!(atom.mask[i] & mobileBit))
        {
            continue;
        }
        const Vec3 x(atom.x[i][0], atom.x[i][1], atom.x[i][2]);
        if ((x.array() < lo.array()).any() || (x.array() > hi.array()).any())
        {
            atom.mask[i] &= ~mobileBit;
            atom.type[i] = fixedType;
            for (int k = 0; k < 3; ++k)
            {
                atom.v[i][k] = atom.omega[i][k] = 0.0;
            }
            ++stopped;
        }
    }
    return sumOverRanks(lmp.communicator(), stopped);
}

} // namespace iceDEM
